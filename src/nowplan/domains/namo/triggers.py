"""Reconsideration triggers for selective replanning (seed 000 IV-B).

The paper's cascade, cheap stages first, each plan examined once per
perceptual event (the belief's ``percept`` counter):

1. *new obstacle*: an object detected after a move's volume was planned
   now meets the volume of a move still ahead.  This alone does not replan:
   it starts stage 2 ("trigger the first stage of reconsideration if any new
   objects were detected that overlap any paths");
2. *shorter path*: plan a path from the start of the moves still ahead to
   the plan's destination in the current belief (known obstacles at their
   clearing cost, known free space, shadows, and fog at its expected
   clearance cost: :mod:`.fogcost`); if it is cheaper than the
   moves still ahead, re-costed in the same belief, by more than
   ``reconsider_gain`` metres (the paper's "one meter"), or the old path has
   become impossible, replan symbolically.  Stage 2 also runs after any other
   perceptual event (a much better or a moved estimate, an object gone),
   which is the "full reconsideration after a new estimate" of Fig. 9;
3. *placement*: a placement still ahead that a new object now overlaps
   replans at once ("for any object placement that overlaps a new object,
   trigger symbolic replanning").

The executive's selective mechanism can add its domain-independent
cost-increase trigger (operator costs re-evaluated in the new belief);
``nowplan reproduce 000`` turns it off for the seed's selective replanning,
whose triggers are the two of its Sec. V (see docs/namo.md).
"""

from __future__ import annotations

from collections.abc import Callable
import logging
from typing import Any

from nowplan.domains.namo.belief import NamoBelief, k_of
from nowplan.domains.namo.fogcost import fog_cost_spread
from nowplan.domains.namo.geometry import Pt, Region
from nowplan.domains.namo.params import Params
from nowplan.domains.namo.paths import INF, PathPlanner

log = logging.getLogger(__name__)

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


def remaining_places(plan: Any) -> list[tuple[str, Region]]:
    """The placements still ahead in a plan: (object, the disc its placed box needs free)."""
    out = []
    for a in plan.actions:
        if a.name == "Place" and isinstance(a.args[8], Region):
            out.append((str(a.args[0]), a.args[8]))
    return out


def make_triggers(params: Params) -> tuple[Trigger, ...]:
    def path_check(plan: Any, belief: NamoBelief, new: list[str]) -> str | None:
        """Stage 2 (once per plan and perceptual state, whichever stage asks)."""
        memo: dict[int, tuple[Any, int, str | None]] = belief.__dict__.setdefault("_path_check_memo", {})
        hit = memo.get(id(plan))
        if hit is not None and hit[0] is plan and hit[1] == belief.percept:
            return None  # already answered (and acted on) for this perceptual state
        out = _path_check(plan, belief, new)
        memo[id(plan)] = (plan, belief.percept, out)
        return out

    def _path_check(plan: Any, belief: NamoBelief, new: list[str]) -> str | None:
        """Is a path cheaper than the moves still ahead by more than the gain?"""
        goal = destination(plan)
        regions, at_start = remaining_moves(plan, belief)
        if goal is None or not regions or not at_start or regions[-1].end != goal:
            return None
        pp = PathPlanner.of(belief, regions[0].foresight)
        old = sum(pp.segment_cost(r.start, r.end) for r in regions)
        path = pp.path(regions[0].start, goal)
        if path is None:
            return None
        cost = pp.polyline_cost(path)
        why = f" (new obstacle {', '.join(new)} on the planned path)" if new else ""
        if cost < INF and old == INF:
            return "the planned path is blocked (something there cannot be moved); another exists" + why
        if cost == INF or cost >= old - params.reconsider_gain:
            return None
        # the gain must also stand out of the noise of the fog's expected cost (fogcost.py)
        spread = 0.0
        if params.reconsider_sd > 0:
            spread = fog_cost_spread(
                belief, list(zip(path, path[1:])), [(r.start, r.end) for r in regions],
            )
        log.debug(
            "stage 2: planned %.2f, new %.2f, gain %.2f, fog spread %.2f (needs > %.2f)%s",
            old, cost, old - cost, spread, params.reconsider_gain + params.reconsider_sd * spread, why,
        )
        if old - cost > params.reconsider_gain + params.reconsider_sd * spread:
            return f"a path shorter by {old - cost:.1f} m exists" + why
        return None

    def new_on_path(plan: Any, belief: NamoBelief) -> list[str]:
        """Stage 1: objects detected after a move still ahead was planned that meet its volume."""
        regions, _ = remaining_moves(plan, belief)
        k = k_of(params.eps_clear)
        out: list[str] = []
        for o in belief.free_objects():
            if any(o.first_seen > r.stamp and r.hits_box(o.box, k * o.sigma) for r in regions):
                out.append(o.name)
        return out

    def new_obstacle(plan: Any, belief: Any) -> str | None:
        """New objects on the path start stage 2; on a placement they replan at once."""
        if not isinstance(belief, NamoBelief):
            return None
        places = remaining_places(plan)
        if not places and not remaining_moves(plan, belief)[1]:
            return None  # stage 2 compares paths from a move's start: wait until the robot is at one

        def check() -> str | None:
            for obj, spot in places:
                if not belief.clear(spot, frozenset({obj}), params.eps_clear):
                    return f"a new obstacle overlaps the placement of {obj}"
            new = new_on_path(plan, belief)
            return path_check(plan, belief, new) if new else None

        return _memo(belief, "new_obstacle", plan, check)

    def shorter_path(plan: Any, belief: Any) -> str | None:
        """Stage 2 after any perceptual event (Fig. 9: a better estimate opens a shorter way)."""
        if not isinstance(belief, NamoBelief):
            return None
        regions, at_start = remaining_moves(plan, belief)
        if not regions or not at_start or all(r.stamp >= belief.percept for r in regions):
            return None
        return _memo(belief, "shorter_path", plan, lambda: path_check(plan, belief, []))

    return (new_obstacle, shorter_path)
