"""Reconsideration triggers for selective replanning (seed 000 IV-B).

Two stages, both cheap and both keyed on the belief's perception counter
so each plan is examined once per perceptual event:

1. *new obstacle*: an object detected after a move's volume was planned
   now meets the volume of a move still ahead;
2. *shorter path*: after any perceptual event (a new object, a much better
   or a moved estimate, an object gone or moved), plan a path from the
   robot to the plan's destination in the current belief; if it is shorter
   (in path cost) than the moves still ahead by more than
   ``reconsider_gain`` metres, reconsider.

The executive's selective mechanism also fires on a cost increase of the
remaining steps (operator costs re-evaluated in the new belief).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nowplan.domains.namo.belief import NamoBelief, k_of
from nowplan.domains.namo.geometry import Pt, Region
from nowplan.domains.namo.params import Params
from nowplan.domains.namo.paths import INF, PathPlanner

Trigger = Callable[[Any, Any], "str | None"]


def remaining_moves(plan: Any, belief: NamoBelief) -> tuple[list[Region], bool]:
    """The volumes of the moves still ahead, and whether the robot stands at the first one's start."""
    regions = [a.args[2] for a in plan.actions if a.name == "Move" and isinstance(a.args[2], Region)]
    if not regions:
        return [], False
    here = belief.nominal()
    for i, r in enumerate(regions):
        if r.start == here:
            return regions[i:], True
    for i, r in enumerate(regions):
        if r.end == here:
            return regions[i + 1 :], False
    return regions, False


def destination(plan: Any) -> Pt | None:
    for a in plan.goal.atoms:
        if a.predicate == "RobotAt" and a.value is True:
            return a.args[0]  # type: ignore[no-any-return]
    return None


def _memo(belief: NamoBelief, name: str, plan: Any, fn: Callable[[], str | None]) -> str | None:
    memo: dict[tuple[str, int], tuple[Any, int, str | None]] = belief.__dict__.setdefault("_trigger_memo", {})
    key = (name, id(plan))
    hit = memo.get(key)
    if hit is not None and hit[0] is plan and hit[1] == belief.percept:
        return None  # already answered for this perceptual state: fire at most once
    out = fn()
    memo[key] = (plan, belief.percept, out)
    return out


def make_triggers(params: Params) -> tuple[Trigger, ...]:
    def new_obstacle(plan: Any, belief: Any) -> str | None:
        if not isinstance(belief, NamoBelief):
            return None

        def check() -> str | None:
            regions, _ = remaining_moves(plan, belief)
            k = k_of(params.eps_clear)
            for r in regions:
                for o in belief.free_objects():
                    if o.first_seen > r.stamp and r.hits_box(o.box, k * o.sigma):
                        return f"new obstacle {o.name} on the planned path ({r})"
            return None

        return _memo(belief, "new_obstacle", plan, check)

    def shorter_path(plan: Any, belief: Any) -> str | None:
        if not isinstance(belief, NamoBelief):
            return None
        goal = destination(plan)
        if goal is None:
            return None

        def check() -> str | None:
            regions, at_start = remaining_moves(plan, belief)
            if not regions or not at_start or all(r.stamp >= belief.percept for r in regions):
                return None
            if regions[-1].end != goal:
                return None
            pp = PathPlanner.of(belief, regions[0].foresight)
            old = sum(pp.segment_cost(r.start, r.end) for r in regions)
            path = pp.path(regions[0].start, goal)
            if path is None:
                return None
            new = pp.polyline_cost(path)
            if new < INF and old == INF:
                return "the planned path is blocked (something there cannot be moved); another exists"
            if new < INF and new < old - params.reconsider_gain:
                return f"a path shorter by {old - new:.1f} m exists"
            return None

        return _memo(belief, "shorter_path", plan, check)

    return (new_obstacle, shorter_path)
