"""Generators for moves and looks: they bind the geometric choices of the plan.

Each is ``fn(bindings, goal, belief, context)`` and yields bindings, best
first.  Moves come from the grid planner (:mod:`.paths`): a path from where
the robot is to the target, string-pulled and cut into straight moves of at
most ``segment`` metres, produced backwards from the target as regression
asks for them.  With foresight on (``context.foresight``) the path planner
treats the epsilon-shadows of uncertain objects as soft costs.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from functools import lru_cache
from typing import Any

from nowplan.core.atoms import Goal, Var
from nowplan.domains.namo.belief import LOOP_LIMIT, NamoBelief
from nowplan.domains.namo.geometry import Box, Pt, Region, point_back
from nowplan.domains.namo.paths import INF, PathPlanner
from nowplan.planning.context import PlanningContext

A, B, SW = Var("a"), Var("b"), Var("sw")
V, R, O, AT, LM, E = Var("v"), Var("r"), Var("o"), Var("at"), Var("lm"), Var("e")
PRE, N = Var("pre"), Var("n")

Bindings = Mapping[Var, Any]
Out = Iterator[dict[Var, Any]]


def foresight(context: Any) -> bool:
    return bool(context is not None and getattr(context, "foresight", False))


# Move requests in the unrestricted pass of a whole-problem call: more than any search within its node
# budget asks (about one per node); the bound only ends a call asking for moves without expanding.
UNRESTRICTED_LIMIT = 1_000_000


def move_request_bound(context: Any) -> int:
    """How many move requests one planning call gets before its move generator gives up.

    A refinement, or the restricted pass of a whole-problem call: ``LOOP_LIMIT``.  The first pass of a
    whole-problem call (:mod:`nowplan.acting.whole`): ``UNRESTRICTED_LIMIT``; its node budget ends it.
    """
    if not isinstance(context, PlanningContext) or not context.whole_problem or context.restricted:
        return LOOP_LIMIT
    return UNRESTRICTED_LIMIT


def robot_at_in(goal: Goal) -> Pt | None:
    """The pose a goal asks the robot to be at, if any."""
    for a in goal.atoms:
        if a.predicate == "RobotAt" and a.value is True:
            p = a.args[0]
            return p if isinstance(p, Pt) else None
    return None


def region(belief: NamoBelief, a: Pt, b: Pt, fs: bool) -> Region:
    return Region(a, b, belief.geom.robot_radius, stamp=belief.percept, foresight=fs)


def gen_move(bindings: Bindings, goal: Goal, belief: NamoBelief, context: Any) -> Out:
    """Where to move from to reach ``?b``: straight from the robot, or the previous waypoint of a path.

    A straight move that an earlier path already chose (a *committed* move,
    e.g. the step being refined) is offered alone while its obstacles can
    be moved: refining a move keeps its swept volume, as BHPN does, instead
    of re-routing locally.  Only replanning the route (after a failure, a
    trigger, or always for aggressive replanning) computes a new path.
    """
    b = bindings.get(B)
    if not isinstance(b, Pt) or belief.planning_loop(context, move_request_bound(context)):
        return
    fs = foresight(context)
    seg = belief.params.segment
    for a in sorted(belief.route_memo.get(b, ())):
        if belief.at(a) and a.dist(b) <= seg + 1e-9 and belief.geom.segment_free(a, b):
            r = region(belief, a, b, fs)
            if _clearable(belief, r) and not _unobservable(belief, r) and not _unseen_blocker(belief, r):
                yield {A: a, SW: r}
                return
    start = belief.nominal()
    if belief.held_manip is not None:  # moves start once what is held has been put down
        start = belief.held_manip.home
    if start.dist(b) < 1e-6:
        return
    good: list[Pt] = []
    for _ in range(2):
        stuck_before = set(belief.unmovable.items())
        pp = PathPlanner.of(belief, fs)
        straight = start.dist(b) <= seg + 1e-9 and belief.geom.segment_free(start, b)
        if straight and pp.segment_cost(start, b) == INF and pp.path(start, b) != [start, b]:
            straight = False  # through something that cannot be moved, while there is another way
        opts: list[Pt] = [start] if straight else []
        path = pp.path(start, b)
        if path is not None and len(path) >= 2:
            prev = point_back(path, seg)
            if prev.dist(b) > 1e-6 and prev not in opts:
                opts.append(prev)
        # only moves whose refinement can succeed: every obstacle in the way can be looked
        # at or moved (finding one that cannot marks it, and the path is planned again)
        good = [a for a in opts if _clearable(belief, region(belief, a, b, fs))]
        seeable = [a for a in good if not _unobservable(belief, r := region(belief, a, b, fs))
                   and not _unseen_blocker(belief, r)]
        if good and not seeable and start.dist(b) > 0.4:
            # a look from the start already failed to reveal the way (fog hidden behind something
            # not seen from there), or to find an object whose shadow is in the way (occluded from
            # there): get there in two moves, looking again from halfway
            mid = belief.geom.grid.snap(Pt.of((start.x + b.x) / 2, (start.y + b.y) / 2))
            if mid not in (start, b) and belief.geom.segment_free(mid, b):
                seeable = [mid]
        good = seeable or good
        if good or set(belief.unmovable.items()) == stuck_before:
            break
    if not good:  # nothing surely refinable: let the refinement try (and fail informatively)
        good = opts
    for a in good:
        if a != start:
            belief.route_memo.setdefault(b, set()).add(a)
        yield {A: a, SW: region(belief, a, b, fs)}


def _unobservable(belief: NamoBelief, r: Region) -> bool:
    """Did a look from the move's start already fail to reveal its volume, with nothing new seen since?

    (Fog hidden behind something the robot cannot see from there: the same
    look would fail again, and a plan that needs it would repeat it.)
    """
    return belief.futile_looks.get((r.view, f"look:{r}")) == belief.percept and not belief.is_observed(r)


def _unseen_blocker(belief: NamoBelief, r: Region) -> bool:
    """Is an object whose shadow (not its body) lies in the move's way one that a look from the move's
    start failed to find, with nothing new seen since?  Its shadow can only shrink by a look from
    elsewhere (issue 14: sensor noise 0.2/m, seed 12: an object seen once, 1 m off, hidden behind
    another from the start; the look was repeated from there, then no plan)."""
    return any(not belief.in_the_way(r, name) and belief.futile_looks.get((r.view, name)) == belief.percept
               for name in belief.blockers(r, belief.params.eps_clear))


def _clearable(belief: NamoBelief, r: Region) -> bool:
    """Can every object in the way be looked at (only its shadow is) or moved somewhere?"""
    from nowplan.domains.namo.placement import manip_options

    for name in belief.blockers(r, belief.params.eps_clear):
        if not belief.in_the_way(r, name):
            continue  # a closer look will probably show the way is clear
        if not manip_options(belief, name, r.start, (r,), (), n=1):
            return False
    return True


def gen_look(bindings: Bindings, goal: Goal, belief: NamoBelief, context: Any) -> Out:
    r = bindings.get(R)
    if isinstance(r, Region):
        yield {V: r.view}


def _posterior(prior: float, meas: float) -> float:
    if prior <= 0:
        return 0.0
    return 1.0 / math.sqrt(1.0 / (prior * prior) + 1.0 / (meas * meas))


# The looser tolerance a look's pre-image asks for when one look suffices whatever the prior (any
# estimate at all: BVRelPose(o) = LOOSE holds as soon as ``o`` is known).
LOOSE = 1e3
# Longest chain of looks from one view point that a plan may ask for to reach a tolerance: a look's
# pre-image asks for a looser tolerance, which another look can achieve, and so on (seed 000's
# regression of belief fluents); past this many looks, looking from here is not worth it.
MAX_LOOKS = 30


def prior_needed(want: float, meas: float, n: int = 1) -> float:
    """The largest prior standard deviation from which ``n`` looks with noise ``meas`` reach ``want``.

    Inverts the Kalman update ``1/post^2 = 1/prior^2 + n/meas^2``: the
    regression of ``BVRelPose(o) = want`` through ``n`` looks is
    ``BVRelPose(o) = prior_needed(want, meas, n)`` (``LOOSE`` when they
    reach ``want`` from any prior).
    """
    if want <= 0:
        return 0.0
    gap = 1.0 / (want * want) - n / (meas * meas)
    if gap <= 0:
        return LOOSE
    return 1.0 / math.sqrt(gap)


def looks_needed(have: float, want: float, meas: float) -> int:
    """How many independent looks with noise ``meas`` take a standard deviation from ``have`` to ``want``."""
    if have <= want:
        return 0
    if want <= 0:
        return MAX_LOOKS + 1
    return max(1, math.ceil((1.0 / (want * want) - 1.0 / (have * have)) * meas * meas - 1e-9))


def look_noise(belief: NamoBelief, v: Pt, at: Pt) -> float:
    """The predicted noise of one measurement of an object at ``at`` taken from ``v`` (sensor and robot)."""
    return math.hypot(belief.sensor.sigma_at(v.dist(at)), belief.robot_sigma)


def gen_look_obj(bindings: Bindings, goal: Goal, belief: NamoBelief, context: Any) -> Out:
    """Look ``?n`` times at an object from where the robot will be, to know its position to within ``?e``.

    ``?n`` is the number of looks (at the predicted noise for that distance)
    that take the current estimate to ``?e``; the action's pre-image asks for
    the looser tolerance from which those ``n`` looks reach ``?e``, so if the
    estimate is worse when the look comes (or the robot less well localised)
    the planner regresses that tolerance through another look.  A noisy
    sensor is thus answered by looks, not by no plan; more than
    ``MAX_LOOKS`` looks from here are not offered.
    """
    name = bindings.get(O)
    est = belief.objects.get(name) if isinstance(name, str) else None
    if est is None or name == belief.held:
        return
    want = float(bindings.get(E, belief.params.eps_pick))
    v = robot_at_in(goal) or belief.nominal()
    d = v.dist(est.center)
    if d > belief.sensor.range - 0.2 or belief.futile_looks.get((v, str(name))) == belief.percept:
        return
    meas = look_noise(belief, v, est.center)
    n = max(1, looks_needed(est.sigma, want, meas))
    if n > MAX_LOOKS:
        return
    yield {V: v, AT: est.center, N: n, PRE: prior_needed(want, meas, n)}


@lru_cache(maxsize=65536)
def _sigma_to_clear(region: Region, box: Box, k: float) -> float:
    """The largest standard deviation whose k-sigma shadow of ``box`` stays out of ``region`` (0: none).

    A pure function of its (immutable) arguments, memoised: the planner asks it for the same region
    and estimate at every node that needs the region clear."""
    if region.hits_box(box, 0.0):
        return 0.0
    lo, hi = 0.0, 4.0 / max(k, 1e-6)
    if not region.hits_box(box, k * hi):
        return hi
    for _ in range(24):
        mid = (lo + hi) / 2
        if region.hits_box(box, k * mid):
            hi = mid
        else:
            lo = mid
    return lo


def gen_look_landmark(bindings: Bindings, goal: Goal, belief: NamoBelief, context: Any) -> Out:
    """Look at the nearest landmark in sight of where the robot will be."""
    want = float(bindings.get(E, belief.params.eps_loc))
    v = robot_at_in(goal) or belief.nominal()
    key = ("look_landmark", v, want)
    c = belief.cache()  # the same view point and tolerance at many nodes of one search
    if key not in c:
        c[key] = _landmarks_in_sight(belief, v, want)
    for name in c[key]:
        yield {V: v, LM: name}


def _landmarks_in_sight(belief: NamoBelief, v: Pt, want: float) -> list[str]:
    """The (at most two) nearest landmarks a look from ``v`` sees, if one look localises to ``want``."""
    geom = belief.geom
    options = []
    for name, p in geom.landmarks:
        d = v.dist(p)
        if d > belief.sensor.landmark_range:
            continue
        ks = geom.grid.line_cells(v, p)
        own, tgt = geom.grid.cell(v), geom.grid.cell(p)
        if any(geom.wall_mask[k] for k in ks.tolist() if k not in (own, tgt)):
            continue
        if _posterior(belief.robot_sigma, belief.sensor.landmark_sigma) <= want:
            options.append((d, name))
    return [name for _, name in sorted(options)[:2]]


def gen_look_clear(bindings: Bindings, goal: Goal, belief: NamoBelief, context: Any) -> Out:
    """Look again at an object whose shadow, not its body, meets a region that must be clear.

    The look is expected (most likely observation: the mean stays) to shrink
    the shadow out of the region.  Its pre-image asks for the object's
    position known to the tolerance from which this one look shrinks the
    shadow enough (``prior_needed``), so a noisy sensor plans more looks
    (``LookObj``) first; offered only when that takes at most ``MAX_LOOKS``.
    """
    from nowplan.domains.namo.belief import k_of

    r, ex = bindings.get(R), bindings.get(Var("ex"))
    if not isinstance(r, Region) or not isinstance(ex, frozenset):
        return
    v = robot_at_in(goal) or belief.nominal()
    k = k_of(belief.params.eps_clear)
    for name in belief.blockers(r, belief.params.eps_clear, ex):
        est = belief.objects[name]
        if belief.in_the_way(r, name) or belief.futile_looks.get((v, name)) == belief.percept:
            continue
        d = v.dist(est.center)
        if d > belief.sensor.range - 0.2:
            continue
        need = _sigma_to_clear(r, est.box, k)
        meas = look_noise(belief, v, est.center)
        n = max(1, looks_needed(est.sigma, need, meas))
        if need <= 0 or n > MAX_LOOKS:
            continue
        yield {O: name, V: v, AT: est.center, Var("exo"): ex | {name}, N: n, PRE: prior_needed(need, meas, n)}
