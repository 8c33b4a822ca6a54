"""The seed's means-ends planner behind the executive's ``domain-planner`` switch.

The executive calls a domain planner with the regression planner's
signature ``(domain, objects, belief, goal, levels, config, context, rng)``.
This adapter plans with :func:`~nowplan.domains.pieces.meansends.plan_means_ends`
from the belief's point state (the observed world model) and shapes the plan
for the levels it was asked at:

* at an abstract level where arm moves are not primitive and no step has
  been refined yet (HPN's top level, ``hpn+…``), it returns the plan's
  *abstraction*: its piece moves only, with pre-images at that level (where
  the pieces are, not where the arm is).  The executive refines each piece
  move, again with the means-ends rule, into an arm move and the piece move;
* otherwise (a refinement, or a ``flat+…`` strategy) it returns the concrete
  plan, every step primitive.

``config`` (time limits) and ``context`` (foresight) do not apply to the
rule, which plans in milliseconds and is deterministic; ``rng`` is passed on
only to keep the signature.
"""

from __future__ import annotations

import random
from collections.abc import Mapping
from typing import Any

from nowplan.acting.monitor_support import plan_from_actions, state_of
from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.domains.pieces.meansends import plan_means_ends
from nowplan.planning.plan import PlanResult, PlanStatus


def abstract_level(levels: LevelMap, domain: Domain) -> bool:
    """``levels`` is an untouched abstract map at which the arm's moves are not primitive."""
    move_arm = domain.operator_map["move_arm"]
    return not levels.overrides and not levels.floors and not all(
        p.criticality > levels.top for p in move_arm.preconditions)


def means_ends_for_executive(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap,
    config: Any = None,
    context: Any = None,
    rng: random.Random | None = None,
) -> PlanResult:
    """The means-ends plan from the belief's state to ``goal``, abstract at HPN's top level."""
    state = state_of(belief)
    res = plan_means_ends(domain, objects, state, goal, rng)
    if not res.solved or res.plan is None or not abstract_level(levels, domain):
        return res
    pieces = [a for a in res.plan.actions if a.name != "move_arm"]
    plan = plan_from_actions(domain, pieces, goal, levels)
    if plan is None or not domain.satisfies(state, plan.preimage(0)):
        return res  # cannot happen for a consistent model: the concrete plan is as good
    return PlanResult(PlanStatus.SOLVED, plan, res.reason, expanded=res.expanded,
                      cpu_time_s=res.cpu_time_s, method="means-ends (abstract)")


__all__ = ["abstract_level", "means_ends_for_executive"]
