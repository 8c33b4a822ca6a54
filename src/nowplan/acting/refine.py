"""Refinements that make progress: no swap of a refined step for a more abstract sibling.

HPN refines an abstract step ω by planning its pre-image at ``NextLevel(α, ω)`` (seed 002
Alg. 1 line 7), which makes ω, and only ω, one criticality class more concrete.  The plan
found may then use a *sibling* (another instance of ω's operator) that still hides the
precondition just exposed, because hiding it makes the sibling cheaper: on pieces, refining
``move_arm(a, b)`` (the arm must be at ``a``) chose an abstract ``move_arm(c, b)`` from a
cell ``c`` nearer ``b``; refining that chose one from a cell nearer still, one pushed plan
per cell, until the plan stack was 64 deep.  Such a chain is a recursion of refinements
within one action, bounded only by the number of instances.

:func:`refine_without_swaps` checks the plan made for a refinement: when a step is more
abstract than an instance of its operator refined higher up the chain (an override of the
level map), the refinement is planned again with that operator *floored* at that level
(:meth:`nowplan.core.levels.LevelMap.floored`; the floor then holds in every plan below),
until no step is.  Along a chain every push then lowers the lowest refined level of one
operator by at least one class, so the chain is no deeper than the operators have
criticality classes in all; a plan with no such step (marsupial, logistics as measured) is
kept as it was made, with no extra planning.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.core.atoms import Goal
from nowplan.core.levels import LevelMap
from nowplan.planning.plan import Plan

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame


def refine_without_swaps(ex: Executive, new: Plan, goal: Goal, levels: LevelMap, parent: Frame) -> Plan | None:
    """``new`` (made for ``goal`` at ``levels`` to refine a step of ``parent``) if none of its steps
    is more abstract than a refined instance of its operator; else the plan made again with
    those operators floored (None when there is none).  Each round adds or lowers a floor, so
    the rounds are bounded by the operators' criticality classes."""
    plan: Plan | None = new
    while plan is not None:
        floored = levels.floored(s.action for s in plan.steps if s.action is not None)
        if floored is levels:
            return plan
        ex.forget_plan(plan)
        ex.trace.emit("note", plan_id=parent.plan_id,
                      text="executive: the refinement's plan swaps in a more abstract instance of an "
                           "operator refined above it; planning it again with that operator floored "
                           f"({', '.join(f'{n} <= {v}' for n, v in sorted(floored.floors))})")
        levels = floored
        plan = ex.make_plan(goal, levels, parent)
    return None
