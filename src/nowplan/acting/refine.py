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
operator by at least one class, so the chain is no deeper than twice the operators'
criticality classes in all, wherever the floored problems have plans (the check applies
from the second swap in a row: a step that was itself swapped in); a plan with no such
step is kept as it was made, with no extra planning, and so is one whose floored problem
has no plan (then the plan stack's depth limit remains the bound).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.core.atoms import Goal
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.plan import Plan

# the floored attempt's node budget: 4x the nodes the plan it replaces took, at least this; a floored
# problem harder than that (marsupial: a travel whose packing the generators cannot plan from the
# current belief) keeps the plan as made instead of exhausting a search space per refinement
FLOOR_NODES = 200

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame


def refine_without_swaps(ex: Executive, new: Plan, goal: Goal, levels: LevelMap, parent: Frame,
                         refined: Action) -> Plan:
    """``new`` (made for ``goal`` at ``levels`` to refine the step ``refined`` of ``parent``) if
    ``refined`` was not itself swapped in (more abstract, in ``parent``'s plan, than a refined
    instance of its operator) or none of ``new``'s steps is more abstract than a refined instance
    of its operator; else the plan made again with those operators floored.  So one swap is
    refined as seed 002 refines (marsupial's plans swap a travel for a sibling once, and planning
    every such refinement again cost RCHPN up to 25x its planning time), and a second swap in a
    row, the start of a recursion, is not.  When the floored problem has no plan (marsupial: a plane that
    cannot be packed for its travel from the current belief, the seed's generators planning in
    the now), the plan made without the floor is kept, as seed 002 refines: the hierarchy needs
    the sibling there, and the stack's depth limit stays the bound.  The floored attempt may expand
    4x the nodes of the plan it would replace (at least :data:`FLOOR_NODES`).  Each round adds or lowers a
    floor, so the rounds are bounded by the operators' criticality classes."""
    if parent.plan.levels.floored([refined]) is parent.plan.levels:
        return new  # the step refined was no swap: its plan may swap once
    plan = new
    while True:
        floored = levels.floored(s.action for s in plan.steps if s.action is not None)
        if floored is levels:
            return plan
        what = ", ".join(f"{n} <= {v}" for n, v in sorted(floored.floors))
        ex.trace.emit("note", plan_id=parent.plan_id,
                      text="executive: the refinement's plan swaps in a more abstract instance of an "
                           f"operator refined above it; planning it again with that operator floored ({what})")
        expanded = ex.made_with(plan).get("expanded")
        budget = max(FLOOR_NODES, 4 * expanded) if isinstance(expanded, int) else None
        again = ex.make_plan(goal, floored, parent, max_nodes=budget)
        if again is None:
            ex.trace.emit("note", plan_id=parent.plan_id,
                          text=f"executive: no plan with {what}; keeping the refinement's plan as made")
            return plan
        ex.reject_plan(plan, parent, f"swaps in an instance more abstract than one refined above it ({what})")
        plan, levels = again, floored
