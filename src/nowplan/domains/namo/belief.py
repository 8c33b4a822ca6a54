"""The NAMO agent's belief: fog grid, robot pose estimate, one Kalman filter per object.

* ``observed`` — a grid of cells the robot has seen; the rest is *fog*.
  Walls are known in advance; free space is known only once observed.
* the robot's position is Gaussian (mean, isotropic variance); moving adds
  variance, looking at a landmark removes it (a Kalman update).
* every detected object has a Gaussian position estimate (2x2 covariance)
  updated with a Kalman filter from noisy relative measurements; an object
  that should have been seen where it was believed to be and was not is
  dropped (negative information).

Counters: ``version`` changes on every update (caches key on it);
``percept`` changes only on perceptual events that may warrant
reconsideration (a new object, a much better or a moved estimate, an object
gone).  Belief fluents (``BClear``, ``Observed``…) are answered by the
methods at the bottom, which the domain's predicate tests call.

One object's estimate (:class:`ObjectEstimate`) and ``k_of`` are in
:mod:`nowplan.domains.namo.estimate`, the polyline helpers ``along`` and
``heading_to`` in :mod:`nowplan.domains.namo.geometry`; all are re-exported
here (``__all__``).  The Kalman updates from landmarks and detections are in
:mod:`nowplan.domains.namo.sensing` (:meth:`NamoBelief.detect` folds in one detection).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Hashable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from nowplan.core.operators import Action
from nowplan.domains.namo.estimate import ObjectEstimate, k_of
from nowplan.domains.namo.geometry import (Box, Manip, MapGeometry, Pt, Region, along, heading_to, polyline_length,
                                          snap_free)
from nowplan.domains.namo.params import DEFAULT_PARAMS, DEFAULT_SENSOR, Params, Sensor
from nowplan.domains.namo.sensing import detect, looks_to_give_up, sense
from nowplan.planning.context import PlanningContext
from nowplan.worlds.base import Observation

__all__ = [
    "CONTACT_AHEAD",
    "CONTACT_MOVED",
    "CONTACT_REACH",
    "DRAG_MARGIN",
    "DRAG_MARGIN_MAX",
    "LOOP_LIMIT",
    "NamoBelief",
    "ObjectEstimate",
    "along",
    "heading_to",
    "k_of",
]

log = logging.getLogger(__name__)

# Move-generator calls in one refinement (a planning call below the top of a hierarchical plan) that
# signal a planning loop: the generator gives up, the refinement's search ends (planning_gave_up) and
# the level above plans again.  A call that plans the whole problem (``PlanningContext.whole_problem``)
# asks for moves about once per node it expands (4,354 and 9,822 requests for 9 distinct targets on
# domain1?sigma_per_m=0.1 seed 16, where 1,500 starved it, issue 14): its first pass gets moves up to
# its node budget, its second (``restricted``) LOOP_LIMIT (generators.move_request_bound,
# nowplan.acting.whole).
LOOP_LIMIT = 1500
# A move stopped by a contact: the robot's centre could not go on to a point at most this far ahead
# along the commanded path (the controller checks its path in steps of about this length) ...
CONTACT_AHEAD = 0.05
# ... and a later motion whose centre passes within this distance of that point meets the same object
# (unless the object has since moved by more than CONTACT_MOVED)
CONTACT_REACH = 0.08
CONTACT_MOVED = 0.1
# A drag stopped because the dragged object met a wall: the object sits further toward that wall than
# believed (its grasp offset is off by more than the planner allowed for), so later drags of it keep
# this much more room from the walls, up to DRAG_MARGIN_MAX (placement.py)
DRAG_MARGIN = 0.05
DRAG_MARGIN_MAX = 0.2


@dataclass
class NamoBelief:
    geom: MapGeometry
    robot_mean: np.ndarray
    robot_var: float = 0.0004
    params: Params = DEFAULT_PARAMS
    sensor: Sensor = DEFAULT_SENSOR
    observed: np.ndarray = field(default=None)  # type: ignore[arg-type]
    objects: dict[str, ObjectEstimate] = field(default_factory=dict)
    held: str | None = None
    held_manip: Manip | None = None
    grip: tuple[np.ndarray, np.ndarray] | None = None  # held object's offset from the robot, and its covariance
    robot_sym: Pt | None = None
    version: int = 0
    percept: int = 0
    trajectory: list[Pt] = field(default_factory=list)
    bumps: set[int] = field(default_factory=set)  # cells where the robot bumped into a wall
    unmovable: dict[str, int] = field(default_factory=dict)  # object -> percept when no placement was found
    route_memo: dict[Pt, set[Pt]] = field(default_factory=dict)  # target -> starts a path chose (gen_move)
    # (view point, object or "look:<region>") -> percept when a look from there did not localise the
    # object or reveal the region (occluded, out of view): not relied on again until something new is seen
    futile_looks: dict[tuple[Pt, str], int] = field(default_factory=dict)
    # (view point, object) -> (percept, looks from there in a row that did not detect the object): with a
    # sensor that misses visible objects, a look is futile only after looks_to_give_up of them
    look_misses: dict[tuple[Pt, str], tuple[int, int]] = field(default_factory=dict)
    # object -> (point the robot's centre was stopped from reaching by it, its estimated centre then):
    # a blocked move is an observation that the object occupies the way there (see in_contact_way)
    touched: dict[str, list[tuple[Pt, Pt]]] = field(default_factory=dict)
    # object -> extra room (m) its drags keep from the walls, learnt from drags a wall stopped
    drag_margin: dict[str, float] = field(default_factory=dict)
    # manipulation -> the object whose contact stopped its pick path: Fits fails for it.  A look that
    # moved that object's estimate after the plan was made can put it in the way; the same pick
    # would be stopped again, and was, 25 times, until the stall bound ended the run (issue 14)
    blocked_picks: dict[Manip, str] = field(default_factory=dict)
    _cache: dict[Any, Any] = field(default_factory=dict, repr=False)
    _cache_version: int = -1
    _cells: dict[Region, np.ndarray] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        g = self.geom.grid
        if self.observed is None:
            self.observed = np.zeros(g.n, dtype=bool)
        self.observed = self.observed.copy()
        self.robot_mean = np.asarray(self.robot_mean, dtype=float)
        if self.robot_sym is None:
            self.robot_sym = g.snap(self.pose)
        self.observed |= g.disk_mask(self.pose, 0.6)
        self.trajectory.append(self.pose)

    # -- caches ------------------------------------------------------------------
    def cache(self) -> dict[Any, Any]:
        """A dict valid for the current version only."""
        if self._cache_version != self.version:
            self._cache = {}
            self._cache_version = self.version
        return self._cache

    # -- the progress guard's view ---------------------------------------------------------
    def fingerprint(self) -> Hashable:
        """Which situation the agent is in (the progress guard's cycle detection; see
        :func:`nowplan.domains.namo.fingerprint.fingerprint`)."""
        from nowplan.domains.namo.fingerprint import fingerprint

        return fingerprint(self)

    @property
    def planning_heuristic(self) -> Any:
        """The planner's goal-distance estimate from this belief (:mod:`nowplan.domains.namo.heuristic`)."""
        from nowplan.domains.namo.heuristic import estimate

        return estimate

    def planning_loop(self, call: object = None, limit: int = LOOP_LIMIT) -> bool:
        """Has one planning call (``call``: its context) asked for moves far more often than any plan needs?

        Past this bound the move generator gives up for that call, so a search
        that keeps asking for moves from an unchanged belief ends (no plan)
        instead of running to its time limit.  The count is per planning call:
        a search that gave up must not leave the next call (the level above
        replanning after a failed refinement) without any move, which turned
        one hard refinement into "no plan for the goal".  Repeated calls
        without an action are bounded by the executive (``max_refinements``).
        """
        c = self.cache()
        key = ("move_calls", id(call))
        n = c[key][1] + 1 if key in c else 1
        c[key] = (call, n, limit)  # (the call kept alive with its count: its id is not reused meanwhile)
        if n == limit:
            log.warning("planning loop: %d move requests in one planning call; its move generator gives up", n)
        return n >= limit

    def generators_gave_up(self, call: object) -> str | None:
        """Did the move generator give up on planning call ``call`` (whatever kind of call it is)?"""
        hit = self.cache().get(("move_calls", id(call)))
        if hit is None or hit[0] is not call or hit[1] < hit[2]:
            return None
        return f"its move generator gave up after {hit[1]} move requests"

    def planning_gave_up(self, call: object) -> str | None:
        """Why the search of refinement ``call`` should end: its move generator gave up on it (it would
        search on without moves, up to 45,000 nodes and 40 s, before the level above plans again:
        hpn+noshortcuts on domain1?sigma_per_m=0.1 seed 6), or None.  A whole-problem call searches on
        without new moves (its restricted pass, nowplan.acting.whole): no level above plans again."""
        hit = self.cache().get(("move_calls", id(call)))
        if hit is None or hit[0] is not call or hit[1] < hit[2] or (
                isinstance(call, PlanningContext) and call.whole_problem):
            return None
        return f"planning loop: {hit[1]} move requests in one refinement; its move generator gave up"

    def _bump(self, percept: bool = False) -> None:
        self.version += 1
        if percept:
            self.percept += 1

    # -- robot ---------------------------------------------------------------------
    @property
    def pose(self) -> Pt:
        return Pt.of(self.robot_mean[0], self.robot_mean[1])

    @property
    def robot_sigma(self) -> float:
        return math.sqrt(self.robot_var)

    def at(self, p: Pt) -> bool:
        return self.pose.dist(p) <= self.params.at_tol

    def surely_at(self, p: Pt) -> bool:
        """``RobotAt(p)`` in the belief: ``p`` is the pose the planner names for the robot (:meth:`nominal`:
        the end of a completed move, or the cell centre a stopped one is rounded to), or the mean lies
        ``at_sd`` standard deviations inside the tolerance around ``p``.

        The plain mean test (:meth:`at`) takes a move that stopped just inside the tolerance of its
        target for arrival while the true pose, a centimetre away, lies just outside it: the belief
        said "done" and the world did not (issue 14).  With no variance (the world's true state) the
        two tests agree.
        """
        if p == self.nominal():
            return True
        return self.pose.dist(p) + self.params.at_sd * self.robot_sigma <= self.params.at_tol

    def nominal(self) -> Pt:
        """Where the robot is, as a pose the planner names (the last commanded one if still true)."""
        if self.robot_sym is not None and self.at(self.robot_sym):
            return self.robot_sym
        return self.snap_pose()

    def snap_pose(self) -> Pt:
        """The robot's pose as a cell centre the planner can start from (:func:`snap_free`)."""
        return snap_free(self.geom, self.pose, self.params.at_tol)

    # -- objects -------------------------------------------------------------------
    def free_objects(self, exclude: frozenset[str] | set[str] = frozenset()) -> list[ObjectEstimate]:
        """Known objects lying in the world (not held), except ``exclude``."""
        return [o for n, o in sorted(self.objects.items()) if n != self.held and n not in exclude]

    def stuck(self, name: str) -> bool:
        """No way to move this object was found since the last perceptual event."""
        return self.unmovable.get(name) == self.percept

    def object_sigma(self, name: str) -> float | None:
        o = self.objects.get(name)
        return None if o is None else o.sigma

    def blockers(self, region: Region, eps: float, exclude: frozenset[str] = frozenset()) -> list[str]:
        """Objects (not in ``exclude``) whose epsilon-shadow meets the region."""
        key = ("blockers", region, round(eps, 6), exclude)
        c = self.cache()
        if key in c:
            return c[key]  # type: ignore[no-any-return]
        k = k_of(eps)
        out = [o.name for o in self.free_objects(exclude)
               if region.hits_box(o.box, k * o.sigma) or self.in_contact_way(region, o.name)]
        c[key] = out
        return out

    def in_the_way(self, region: Region, name: str) -> bool:
        """Does the object's body (not just its shadow) block the region, as far as the robot knows?"""
        est = self.objects.get(name)
        return est is not None and (region.hits_box(est.box, 0.05) or self.in_contact_way(region, name))

    def in_contact_way(self, region: Region, name: str) -> bool:
        """Would the motion for ``region`` reach a point that ``name`` stopped the robot from reaching?

        The motion is what the world executes: from the robot's pose onto the
        region's start, then along it, if the robot is (nominally) at the
        start; from the start otherwise.  A point counts only if the motion
        gets closer to it than where the motion begins (moving away from a
        contact stays possible), and only while the object's estimate has
        not moved since the contact (it was moved, or seen elsewhere).
        """
        memo = self.touched.get(name)
        est = self.objects.get(name)
        if not memo or est is None or name == self.held:
            return False
        pts = [self.pose, region.start, region.end] if self.at(region.start) else [region.start, region.end]
        for h, was in memo:
            if est.center.dist(was) > CONTACT_MOVED:
                continue
            d = min(Box(h.x, h.y, 0.0, 0.0).distance_to_segment(pts[i], pts[i + 1]) for i in range(len(pts) - 1))
            if d < CONTACT_REACH and d < h.dist(pts[0]) - 1e-3:
                return True
        return False

    def clear(self, region: Region, exclude: frozenset[str], eps: float) -> bool:
        return not self.blockers(region, eps, exclude) and not self.bumped(region)

    def bumped(self, region: Region) -> bool:
        """Did the robot bump into something unseen inside the region (its centre cannot go there)?"""
        if not self.bumps or region.radius <= 0:
            return False
        g = self.geom.grid
        return any(region.hits_box(Box(g.center(c).x, g.center(c).y, 0.0, 0.0), -region.radius + 0.1)
                   for c in self.bumps)

    # -- fog -----------------------------------------------------------------------
    def region_cells(self, region: Region) -> np.ndarray:
        c = self._cells.get(region)
        if c is None:
            g = self.geom.grid
            c = np.nonzero(g.capsule_mask(region.start, region.end, region.radius))[0]
            if len(self._cells) > 4096:
                self._cells.clear()
            self._cells[region] = c
        return c

    def opaque(self) -> np.ndarray:
        """What blocks the view as far as the robot knows: walls and objects (with their shadows)."""
        c = self.cache()
        if "opaque" not in c:
            g = self.geom.grid
            m = self.geom.wall_mask.copy()
            k = k_of(self.params.eps_clear)
            for o in self.free_objects():
                m |= g.box_mask(o.box, k * o.sigma)
            c["opaque"] = m
        return c["opaque"]  # type: ignore[no-any-return]

    def visible_fog(self, region: Region) -> np.ndarray:
        """Fog cells of the region that a look from its view point could reveal."""
        key = ("vfog", region)
        c = self.cache()
        if key not in c:
            cells = self.region_cells(region)
            fog = cells[~self.observed[cells]]
            if fog.size == 0:
                c[key] = fog
            else:
                g = self.geom.grid
                heading = heading_to(region.view, region.centroid)
                seen = g.visible(region.view, fog, self.opaque(), self.sensor.range, heading, self.sensor.fov)
                c[key] = fog[seen]
        return c[key]  # type: ignore[no-any-return]

    def is_observed(self, region: Region) -> bool:
        return int(self.visible_fog(region).size) <= self.params.fog_observed_slack

    def fog_behind(self, region: Region, obj: str) -> bool:
        """Would ``region`` stop counting as observed once ``obj`` is picked up (fog hidden only by it)?"""
        key = ("fog_behind", region, obj)
        c = self.cache()
        if key not in c:
            cells = self.region_cells(region)
            fog = cells[~self.observed[cells]]
            c[key] = False
            if fog.size > self.params.fog_observed_slack:
                g = self.geom.grid
                m = self.geom.wall_mask.copy()
                k = k_of(self.params.eps_clear)
                for o in self.free_objects():
                    if o.name != obj:
                        m |= g.box_mask(o.box, k * o.sigma)
                seen = g.visible(region.view, fog, m, self.sensor.range, heading_to(region.view, region.centroid),
                                 self.sensor.fov)
                c[key] = int(np.count_nonzero(seen)) > self.params.fog_observed_slack
        return bool(c[key])

    # -- updates -----------------------------------------------------------------------
    def update(self, action: Action, obs: Observation) -> None:
        data: dict[str, Any] = obs.data if isinstance(obs.data, dict) else {}
        name = action.name
        looked = self.objects.get(str(action.args[1])) if name in ("LookObj", "LookClear") else None
        touched: Pt | None = None  # where a move stopped by a contact could not go on to
        if name == "Move":
            region = action.args[2]
            assert isinstance(region, Region)
            path = (self.pose, region.start, region.end)
            stop = self._drive(path, float(data.get("traveled", 0.0)))
            if data.get("completed", obs.success):
                self.robot_sym = region.end
            else:
                self.robot_sym = self.snap_pose()
                touched = along(path, stop + CONTACT_AHEAD) if data.get("contacts") else None
        elif name == "Pick":
            self._update_pick(action, data)
        elif name == "Place":
            self._update_place(action, data)
        self._sense(data)
        if touched is not None:
            self._remember_contacts(data, touched)
        if looked is not None and looked.name not in {str(d[0]) for d in data.get("detections", ())}:
            # not detected (occluded, out of view, missed): a look from there is not relied on again
            # until something new is seen.  (A detected object's estimate always tightens by the
            # predicted amount, however little: a chain of looks with a noisy sensor is not futile.)
            # With a sensor that misses visible objects (``miss_prob``), one miss is chance: the look
            # is futile after looks_to_give_up(miss_prob) misses in a row (issue 14 stress runs:
            # at miss 0.3 one miss barred the only view of an object and the search found no plan).
            v = action.args[0]
            if isinstance(v, Pt):
                key = (v, looked.name)
                was = self.look_misses.get(key)
                n = was[1] + 1 if was is not None and was[0] == self.percept else 1
                self.look_misses[key] = (self.percept, n)
                if n >= looks_to_give_up(self.sensor.miss_prob):
                    self.futile_looks[key] = self.percept
        if name == "Look" and isinstance(action.args[0], Pt) and isinstance(action.args[1], Region):
            if not self.is_observed(action.args[1]):  # (fog hidden behind something: not from here)
                self.futile_looks[(action.args[0], f"look:{action.args[1]}")] = self.percept
        self._bump()

    def misses_now(self) -> frozenset[tuple[tuple[Pt, str], int]]:
        """The looks that missed their object since the last perceptual event, with their counts."""
        return frozenset((k, n) for k, (pc, n) in self.look_misses.items() if pc == self.percept)

    def _remember_contacts(self, data: dict[str, Any], h: Pt) -> None:
        """A move stopped by contact: the robot's centre could not reach ``h`` for the objects touched.

        Remembered with each object's estimate (after the contact's own
        update), so that ``BClear`` keeps failing for motions through ``h``
        until the object is moved or seen elsewhere, even when the estimate
        alone (a few centimetres off) says the way is clear.
        """
        for c in data.get("contacts", ()):
            est = self.objects.get(str(c[0]))
            if est is not None:
                self.touched.setdefault(est.name, []).append((h, est.center))

    def _drive(self, path: tuple[Pt, ...], traveled: float) -> float:
        """Dead-reckon ``traveled`` metres (odometry along the commanded path) from where the robot is.

        The controller drives from the robot's actual pose through the
        commanded waypoints after the first (the world does the same), so
        the estimate starts from the current mean, not from the path's first
        point (a planned cell centre up to 0.14 m away): otherwise a drag
        stopped at once would move the estimate, and the object with it.
        """
        if len(path) < 2:
            return 0.0
        pts = [Pt.of(float(self.robot_mean[0]), float(self.robot_mean[1])), *path[1:]]
        planned, done = polyline_length(path), polyline_length(pts)
        stop = traveled * done / planned if planned > 1e-9 else 0.0
        p = along(pts, stop)
        self.robot_mean = np.array([p.x, p.y])
        self.robot_var += (self.params.motion_model * traveled) ** 2
        self.trajectory.append(p)
        return stop

    def _update_pick(self, action: Action, data: dict[str, Any]) -> None:
        o, m = str(action.args[0]), action.args[1]
        assert isinstance(m, Manip)
        self._drive(m.pick_path, float(data.get("traveled", 0.0)))
        if data.get("grasped"):
            self.held, self.held_manip = o, m
            self.robot_sym = m.pick_conf
            est = self.objects.get(o)
            if est is not None:
                self.grip = (est.mean - self.robot_mean, est.cov.copy())
        else:
            est = self.objects.get(o)
            hit = [str(c[0]) for c in data.get("contacts", ()) if str(c[0]) != o]
            if hit:  # the pick path runs into another object: this manipulation does not fit
                self.blocked_picks[m] = hit[0]
            if data.get("missed") and est is not None:  # it is not where we thought: look again
                est.cov = np.eye(2) * max(est.sigma, 0.15) ** 2
                self.percept += 1
            # the way back is dead-reckoned by its odometry: a return that stopped early moved the
            # robot too (before, only a completed return was, and the pose estimate drifted from the
            # truth by up to the pick path's length per miss, while its variance said it was known)
            back = data.get("back", polyline_length(m.pick_path) if data.get("returned") else 0.0)
            if back:
                self._drive(tuple(reversed(m.pick_path)), float(back))
            self.robot_sym = m.home if self.at(m.home) else self.snap_pose()

    def _update_place(self, action: Action, data: dict[str, Any]) -> None:
        o, m = str(action.args[0]), action.args[4]
        if not isinstance(m, Manip) or self.held != o:
            return
        carried = float(data.get("carried", 0.0))
        self._drive(m.carry_path, carried)
        est = self.objects.get(o)
        if est is not None:
            offset, cov = self.grip if self.grip is not None else (np.array(m.offset), np.eye(2) * 0.0004)
            est.mean = self.robot_mean + offset
            est.cov = cov + np.eye(2) * (self.robot_var + 0.0001)
        self.grip = None
        self.held, self.held_manip = None, None
        if data.get("load_bump"):
            self.drag_margin[o] = min(self.drag_margin.get(o, 0.0) + DRAG_MARGIN, DRAG_MARGIN_MAX)
        if carried >= polyline_length(m.carry_path) - 1e-3 or data.get("home"):
            # the return starts at the release configuration only if the drag got there: a drag
            # stopped early leaves the robot where it stopped (not at the return path's start)
            self._drive(m.return_path, float(data.get("returned", 0.0)))
        self.robot_sym = m.home if data.get("home") and self.at(m.home) else self.snap_pose()
        self.percept += 1  # the map changed where the object was and where it went

    def _sense(self, data: dict[str, Any]) -> None:
        sense(self, data)

    def detect(self, name: str, rx: float, ry: float, s: float, size: tuple[float, float]) -> None:
        """Fold in one detection of ``name`` at ``(rx, ry)`` from the robot with noise ``s``
        (:func:`nowplan.domains.namo.sensing.detect`)."""
        detect(self, name, rx, ry, s, size)
