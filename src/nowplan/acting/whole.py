"""A planning call for the whole problem, in two passes when the domain's generators guard against loops.

A refinement (a call below the top of a hierarchical plan) that a domain's generator gives up on
fails, and the level above plans again.  A call for the whole problem (a flat strategy, the online
policy) has no level above, and the same guard decides *which plans it can find*: NAMO's move
generator offers moves for its first 1,500 requests only (``LOOP_LIMIT``), about one per node
expanded, so a search that needs a move later is starved (issue 14: ``flat`` on
``domain1?sigma_per_m=0.1`` seed 16, 50,000 nodes without a plan), while without the guard another
search is lost among moves and expands its 50,000 nodes without a plan where the guarded one finds
one in about 20,000 (``online``, seed 4; ``online`` on ``sigma_per_m=0.08`` seed 5).

So a whole-problem call first searches with the generators unrestricted (they offer moves up to the
search's own node budget) within ``WIDE_SHARE`` of its node budget, and only if that runs out of nodes
searches again as before, with the generators restricted (``PlanningContext.restricted``) and the whole
budget, within the time the first pass left (the two passes share the call's time limit: a second pass
with the whole limit again ran past the run's own limit, and the sweep's runner killed the run without
its reason, NAMO ``domain1?sigma_per_m=0.15`` ``flat`` seed 3).  Beliefs without such a guard (:class:`~nowplan.belief.protocols.GivesUp`) get one call as before.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Mapping
from dataclasses import replace
from typing import Any

from nowplan.belief.protocols import GivesUp, ReportsGiveUp
from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.planning.config import PlannerConfig, _clock
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import PlanResult, PlanStatus

# The share of a whole-problem call's node budget its unrestricted pass gets (10,000 of the default
# 50,000 nodes: the unrestricted searches that succeed on NAMO domain1?sigma_per_m=0.1 expand a few
# thousand; the restricted pass keeps the whole budget, as the single call had before).
WIDE_SHARE = 0.2

Planner = Callable[..., PlanResult]


def plan_whole_problem(
    planner: Planner, domain: Domain, objects: Mapping[str, str | None], belief: Any, goal: Goal,
    levels: LevelMap, config: PlannerConfig, context: PlanningContext, rng: random.Random,
) -> PlanResult:
    """Plan ``goal`` with ``planner`` (regression's signature): unrestricted first, then restricted."""
    if not isinstance(belief, GivesUp) or context.restricted:
        return planner(domain, objects, belief, goal, levels, config, context, rng)
    wide = max(1, int(config.max_nodes * WIDE_SHARE))
    now = _clock(config)
    t0 = now()
    first = planner(domain, objects, belief, goal, levels,
                    replace(config, max_nodes=wide, shortcut_nodes=min(config.shortcut_nodes, wide)), context, rng)
    if first.solved or first.status is not PlanStatus.NODE_LIMIT:
        return first
    narrow = replace(context, extras={**context.extras, "restricted": True})
    left = config.time_limit - (now() - t0)
    if left <= 0.0:  # the first pass ran out of nodes as its time ran out: no time for a second
        return replace(first, status=PlanStatus.TIME_LIMIT,
                       reason=f"time limit of {config.time_limit:g} s reached (unrestricted pass: {first.reason})")
    second = planner(domain, objects, belief, goal, levels, replace(config, time_limit=left), narrow, rng)
    why = belief.generators_gave_up(narrow) if isinstance(belief, ReportsGiveUp) else None
    if second.status is PlanStatus.UNSOLVABLE and why is not None:
        # the restricted pass searched on without new moves: its exhausted space is not a proof that
        # no plan exists, so it ends as the budget it is (NAMO sigma_per_m=0.2 seed 4, online: the run
        # ended "unsolvable: search space exhausted" after the generator's 1,500 move requests)
        second = replace(second, status=PlanStatus.NODE_LIMIT,
                         reason=f"{second.reason} after {why} (restricted pass): not a proof that no plan exists")
    return replace(
        second, cpu_time_s=first.cpu_time_s + second.cpu_time_s, expanded=first.expanded + second.expanded,
        generated=first.generated + second.generated,
        attempts=(*first.attempts, f"unrestricted pass: {first.reason}", *second.attempts),
    )
