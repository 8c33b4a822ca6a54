"""The simulated NAMO world: true robot and object poses, noisy motion and sensing.

The world never reads the agent's belief.  Actions carry the geometric
plan the agent made (paths, the pose it expects an object at); the world
executes them against the truth: a move stops at the first contact with an
object the agent did not know about (and reports the contact), a grasp
misses when the object is not where the agent expected it or by chance,
dragging stops when the object or robot would hit something.  Sensing is
relative to the robot's true pose: visible cells (a cone of given range and
field of view, occluded by walls and objects), noisy object positions and
landmark bearings.  Every random draw comes from the world's seeded RNG.
"""

from __future__ import annotations

import logging
import math
import random
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from nowplan.core.operators import Action
from nowplan.domains.namo.geometry import Box, Manip, MapGeometry, Pt, Region, shapely
from nowplan.domains.namo.params import DEFAULT_NOISE, DEFAULT_PARAMS, DEFAULT_SENSOR, Noise, Params, Sensor
from nowplan.worlds.base import Observation

if TYPE_CHECKING:
    from nowplan.domains.namo.belief import NamoBelief

log = logging.getLogger(__name__)

NUDGE = 0.25  # an exogenous change moves an object by up to this much (m)
STEP = 0.05  # collision checking resolution along paths (m)
GRAZE = 0.03  # contacts shallower than this are tolerated (m)


@dataclass
class TrueObject:
    name: str
    box: Box
    appear_after: int | None = None  # appears (exogenously) before this many actions have run


class NamoWorld:
    def __init__(
        self,
        geom: MapGeometry,
        robot: Pt,
        objects: Sequence[TrueObject],
        *,
        sensor: Sensor = DEFAULT_SENSOR,
        noise: Noise = DEFAULT_NOISE,
        seed: int = 0,
        params: Params = DEFAULT_PARAMS,
        exogenous_prob: float = 0.0,
    ) -> None:
        self.geom = geom
        self.params = params  # the tolerances the goal is judged with in the world (true_state)
        self.exogenous_prob = exogenous_prob  # after an action, somebody nudges an object
        self.sensor = sensor
        self.noise = noise
        self.rng = random.Random(seed)
        self.robot = np.array([robot.x, robot.y], dtype=float)
        self.objects: dict[str, Box] = {o.name: o.box for o in objects if o.appear_after is None}
        self.pending = sorted(
            ((o.appear_after, o.name, o.box) for o in objects if o.appear_after is not None),
            key=lambda x: (x[0], x[1]),
        )
        self.held: str | None = None
        self.grip: np.ndarray = np.zeros(2)
        self._hit_at: tuple[float, float] | None = None  # where the last motion touched something
        self._hit_load = False  # ... and whether the dragged object, not the robot, touched it
        self.actions = 0
        self.failures = 0
        self.contacts = 0
        self.drives = 0  # base motions: moves, and the approach and return drives of picks and places
        self._wall_geom = geom.wall_shape
        # the robot's grasp controller aims at the agent's latest estimate of the object
        # (set by the episode; without it the grasp aims where the plan expected the object)
        self.grasp_estimate: Callable[[str], Pt | None] | None = None

    # -- truth ------------------------------------------------------------------
    @property
    def pose(self) -> Pt:
        return Pt.of(self.robot[0], self.robot[1])

    def true_state(self) -> NamoBelief:
        """The world as a belief with perfect knowledge (for judging the goal at the end of a run).

        The robot's pose and every object's box exactly (no variance), what is held, and every
        cell observed; the domain's predicates test it with the agent's tolerances (``params``).
        A held object's grasp (the ``Manip``) is not the world's to know: ``Holding`` is false on it.
        """
        from nowplan.domains.namo.belief import NamoBelief, ObjectEstimate

        b = NamoBelief(self.geom, self.robot.copy(), robot_var=0.0, params=self.params, sensor=self.sensor,
                       observed=np.ones(self.geom.grid.n, dtype=bool))
        for name, box in sorted(self.objects.items()):
            b.objects[name] = ObjectEstimate(name, np.array([box.cx, box.cy]), np.zeros((2, 2)), (box.w, box.h), 0)
        b.held = self.held
        return b

    # -- faults ----------------------------------------------------------------------
    def set_faults(self, *, failure_prob: float | None = None, exogenous_prob: float | None = None) -> None:
        """``nowplan run --failure-prob/--exogenous-prob``.

        A failure is the domain's own: a motion (a move, the drive of a pick or a drag) that stops
        short, at 30-80 % of its length, or a grasp that misses (``noise.move_fail`` and
        ``noise.grasp_fail``, both set to ``failure_prob``).  An exogenous change: after an action,
        with probability ``exogenous_prob``, an object lying in the world (not held, not touching
        the robot) is pushed by up to ``NUDGE`` metres to where it fits.
        """
        for name, p in (("failure_prob", failure_prob), ("exogenous_prob", exogenous_prob)):
            if p is not None and not 0.0 <= p <= 1.0:
                raise ValueError(f"{name} must be in [0, 1], got {p}")
        if failure_prob is not None:
            self.noise = replace(self.noise, move_fail=failure_prob, grasp_fail=failure_prob)
        if exogenous_prob is not None:
            self.exogenous_prob = exogenous_prob

    def _nudge(self) -> list[str]:
        """An exogenous change: somebody pushes an object (if one can move without touching anything)."""
        names = [n for n in sorted(self.objects) if n != self.held]
        if not names:
            return []
        name = self.rng.choice(names)
        box = self.objects[name]
        a, r = self.rng.uniform(0.0, 2 * math.pi), self.rng.uniform(0.5 * NUDGE, NUDGE)
        moved = box.moved(Pt.of(box.cx + r * math.cos(a), box.cy + r * math.sin(a)))
        near = self.geom.robot_radius + 0.1
        if (self.box_hits(moved, name) is not None or moved.distance_to_segment(self.pose, self.pose) < near
                or box.distance_to_segment(self.pose, self.pose) < near):
            return []
        self.objects[name] = moved
        return [f"{name} pushed from {box.center} to {moved.center}"]

    def _obstacles(self, ignore: str | None) -> list[tuple[str, Any]]:
        sh = shapely()
        out: list[tuple[str, Any]] = [("wall", self._wall_geom)]
        for name, box in sorted(self.objects.items()):
            if name != ignore and name != self.held:
                out.append((name, sh.box(*box.bounds)))
        return out

    def first_hit(
        self, xs: np.ndarray, ys: np.ndarray, carrying: str | None = None, start: Pt | None = None,
    ) -> tuple[int, str | None]:
        """Index of the first sample where the robot (or the object it drags) touches something.

        With ``start`` (where the robot is before the motion), an object the
        robot already touches there (e.g. one just put down a little closer
        than planned) stops it only if the motion goes deeper into it: the
        robot can back away from what it touches.
        """
        sh = shapely()
        first, what = len(xs), None
        self._hit_load = False
        if not len(xs):
            return first, what
        pts = sh.points(np.stack([xs, ys], axis=1))
        reach = self.geom.robot_radius - GRAZE
        obstacles = self._obstacles(carrying)
        here = sh.Point(start.x, start.y) if start is not None else None
        for name, geom in obstacles:
            limit = reach
            if here is not None and name != "wall":
                limit = min(reach, float(geom.distance(here)) - 1e-3)
            hit = np.nonzero(sh.distance(geom, pts) < limit)[0]
            if hit.size and hit[0] < first:
                first, what = int(hit[0]), name
        if carrying is not None:
            b = self.objects[carrying]
            hw, hh = b.w / 2 - GRAZE, b.h / 2 - GRAZE
            cx, cy = xs + self.grip[0], ys + self.grip[1]
            boxes = sh.box(cx - hw, cy - hh, cx + hw, cy + hh)
            for name, geom in obstacles:
                hit = np.nonzero(sh.intersects(geom, boxes))[0]
                if hit.size and hit[0] < first:
                    first, what = int(hit[0]), name
                    self._hit_load = True
        return first, what

    def robot_hits(self, x: float, y: float) -> str | None:
        """What the robot's disc at (x, y) would touch: 'wall', an object's name, or None."""
        i, what = self.first_hit(np.array([x]), np.array([y]))
        return what if i == 0 else None

    def box_hits(self, box: Box, ignore: str) -> str | None:
        sh = shapely()
        g = sh.box(box.cx - box.w / 2 + GRAZE, box.cy - box.h / 2 + GRAZE,
                   box.cx + box.w / 2 - GRAZE, box.cy + box.h / 2 - GRAZE)
        for name, geom in self._obstacles(ignore):
            if geom.intersects(g):
                return name
        return None

    # -- motion ---------------------------------------------------------------------
    def _follow(self, path: Sequence[Pt], carrying: str | None = None) -> tuple[float, str | None, bool]:
        """Drive along ``path``; returns (distance along the plan, what was hit, completed).

        The controller drives from the true pose through the commanded
        waypoints (map frame); it stops before the first contact, or early
        with probability ``move_fail``.
        """
        if len(path) < 2:
            return 0.0, None, True
        pts = [Pt(float(self.robot[0]), float(self.robot[1])), *path[1:]]
        xs: list[float] = []
        ys: list[float] = []
        ds: list[float] = []
        done = 0.0
        for i in range(len(pts) - 1):
            a, b = pts[i], pts[i + 1]
            L = a.dist(b)
            n = max(1, int(math.ceil(L / STEP)))
            for s in range(1, n + 1):
                t = s / n
                xs.append(a.x + (b.x - a.x) * t)
                ys.append(a.y + (b.y - a.y) * t)
                ds.append(done + L * t)
            done += L
        planned = sum(path[i].dist(path[i + 1]) for i in range(len(path) - 1))
        scale = planned / done if done > 0 else 1.0  # odometry is reported along the commanded path
        limit = len(xs)
        if self.noise.move_fail and self.rng.random() < self.noise.move_fail:
            stop = done * self.rng.uniform(0.3, 0.8)
            limit = next((i for i, d in enumerate(ds) if d > stop), len(xs))
        first, hit = self.first_hit(np.array(xs[:limit]), np.array(ys[:limit]), carrying, start=pts[0])
        self._hit_at = (xs[first], ys[first]) if first < limit else None
        last = min(first, limit) - 1
        if last >= 0:
            self.robot = np.array([xs[last], ys[last]])
            if carrying is not None:
                self.objects[carrying] = self.objects[carrying].moved(
                    Pt(xs[last] + self.grip[0], ys[last] + self.grip[1]))
        traveled = (ds[last] if last >= 0 else 0.0) * scale
        if first < limit:
            return traveled, hit, False
        return traveled, None, limit == len(xs)

    def _jitter_end(self, length: float) -> None:
        s = self.noise.motion_per_m * length
        if s <= 0:
            return
        x = self.robot[0] + self.rng.gauss(0.0, s)
        y = self.robot[1] + self.rng.gauss(0.0, s)
        if self.robot_hits(x, y) is None:
            self.robot = np.array([x, y])

    # -- sensing ----------------------------------------------------------------------
    def sense(self, heading: float | None, fov: float, rng: float) -> dict[str, Any]:
        g = self.geom.grid
        origin = self.pose
        reach = max(rng, self.sensor.landmark_range if heading is not None else rng)
        near = np.nonzero(np.hypot(g.xs - origin.x, g.ys - origin.y) <= reach)[0]
        opaque = self.geom.wall_mask.copy()
        for name, box in self.objects.items():
            if name != self.held:
                opaque |= g.box_mask(box)
        seen = g.visible(origin, near, opaque, reach, heading, fov)
        cells = near[seen]
        d = np.hypot(g.xs[cells] - origin.x, g.ys[cells] - origin.y)
        fog_cells = cells[d <= rng]
        oc = g.cell(origin)
        oi, oj = g.ij(oc)
        rel = np.stack([fog_cells % g.nx - oi, fog_cells // g.nx - oj], axis=1) if fog_cells.size else np.zeros((0, 2), int)
        cell_set = set(fog_cells.tolist())
        detections = []
        for name, box in sorted(self.objects.items()):
            if name == self.held:
                continue
            bc = np.nonzero(g.box_mask(box))[0].tolist()
            if not any(c in cell_set for c in bc):
                continue
            if self.sensor.miss_prob and self.rng.random() < self.sensor.miss_prob:
                continue
            dist = box.center.dist(origin)
            s = self.sensor.sigma_at(dist)
            rx = box.cx - self.robot[0] + self.rng.gauss(0.0, s)
            ry = box.cy - self.robot[1] + self.rng.gauss(0.0, s)
            detections.append((name, rx, ry, s, box.w, box.h))
        landmarks = []
        if heading is not None:
            all_cells = set(cells.tolist())
            for name, p in self.geom.landmarks:
                if g.cell(p) in all_cells and p.dist(origin) <= self.sensor.landmark_range:
                    s = self.sensor.landmark_sigma
                    landmarks.append((name, p.x - self.robot[0] + self.rng.gauss(0, s),
                                      p.y - self.robot[1] + self.rng.gauss(0, s), s))
        return {"visible": rel.tolist(), "detections": detections, "landmarks": landmarks}

    def _contact(self, name: str) -> list[tuple[str, float, float, float, float, float]]:
        if name not in self.objects:
            return []
        self.contacts += 1
        box = self.objects[name]
        s = 0.05
        return [(name, box.cx - self.robot[0] + self.rng.gauss(0, s), box.cy - self.robot[1] + self.rng.gauss(0, s),
                 s, box.w, box.h)]

    # -- actions ----------------------------------------------------------------------
    def execute(self, action: Action) -> Observation:
        exo: list[str] = []
        while self.pending and self.pending[0][0] <= self.actions:
            _, name, box = self.pending.pop(0)
            if box.distance_to_segment(self.pose, self.pose) > self.geom.robot_radius + 0.1:
                self.objects[name] = box
                exo.append(f"obstacle {name} appeared at {box.center}")
        self.actions += 1
        handler = getattr(self, "_do_" + action.name, None)
        if handler is None:
            from nowplan.errors import ExecutionError

            raise ExecutionError(f"the NAMO world cannot execute {action}")
        self._hit_at = None
        ok, data, reason = handler(*action.args)
        if self.exogenous_prob and self.rng.random() < self.exogenous_prob:
            exo.extend(self._nudge())
        # the bumper felt where the robot's own disc met a wall (not the object it drags: the robot
        # itself can stand where a dragged object was stopped)
        if self._hit_at is not None and reason.endswith("by wall"):
            if self._hit_load:  # the drag felt the object meet a wall
                data["load_bump"] = True
            else:
                data["bump"] = (self._hit_at[0] - self.robot[0], self._hit_at[1] - self.robot[1])
        near = self.sense(None, 2 * math.pi, self.sensor.near_range)
        for k in ("visible", "detections"):
            data[k] = list(data.get(k, [])) + near[k]
        if not ok:
            self.failures += 1
        info: dict[str, Any] = {}
        if reason:
            info["reason"] = reason
        seen = sorted({d[0] for d in data.get("detections", ())} | {c[0] for c in data.get("contacts", ())})
        if seen:
            info["seen"] = seen
        log.debug("world %s: ok=%s %s", action, ok, reason)
        return Observation(ok, data, tuple(exo), info)

    def _do_Move(self, a: Pt, b: Pt, region: Region) -> tuple[bool, dict[str, Any], str]:
        self.drives += 1
        traveled, hit, done = self._follow((self.pose, a, b))  # onto the planned segment, then along it
        data: dict[str, Any] = {"traveled": traveled, "completed": done}
        if hit is not None:
            data["contacts"] = self._contact(hit)
            return False, data, f"move blocked by {hit}"
        if not done:
            return False, data, "move stopped early"
        self._jitter_end(traveled)
        return True, data, ""

    def _look(self, heading: float) -> tuple[bool, dict[str, Any], str]:
        return True, self.sense(heading, self.sensor.fov, self.sensor.range), ""

    def _do_Look(self, v: Pt, region: Region) -> tuple[bool, dict[str, Any], str]:
        c = region.centroid
        return self._look(math.atan2(c.y - self.robot[1], c.x - self.robot[0]))

    def _looks(self, heading: float, n: int) -> tuple[bool, dict[str, Any], str]:
        """``n`` looks the same way: every detection and landmark sighting, each with its own noise."""
        ok, data, why = self._look(heading)
        for _ in range(max(int(n), 1) - 1):
            more = self.sense(heading, self.sensor.fov, self.sensor.range)
            data["detections"] = [*data["detections"], *more["detections"]]
            data["landmarks"] = [*data["landmarks"], *more["landmarks"]]
        return ok, data, why

    def _do_LookObj(self, v: Pt, obj: str, at: Pt, eps: float, pre: float = 0.0,
                    n: int = 1) -> tuple[bool, dict[str, Any], str]:
        return self._looks(math.atan2(at.y - self.robot[1], at.x - self.robot[0]), n)

    def _do_LookClear(self, v: Pt, obj: str, at: Pt, region: Region, ex: Any, exo: Any,
                      pre: float = 0.0, n: int = 1) -> tuple[bool, dict[str, Any], str]:
        return self._looks(math.atan2(at.y - self.robot[1], at.x - self.robot[0]), n)

    def _do_LookLandmark(self, v: Pt, lm: str, eps: float) -> tuple[bool, dict[str, Any], str]:
        p = self.geom.landmark(lm)
        return self._look(math.atan2(p.y - self.robot[1], p.x - self.robot[0]))

    def _do_Pick(self, obj: str, m: Manip, home: Pt, pc: Pt, hidden: Any = None) -> tuple[bool, dict[str, Any], str]:
        self.drives += len(m.pick_path) > 1
        traveled, hit, done = self._follow(m.pick_path)
        data: dict[str, Any] = {"traveled": traveled, "grasped": False, "returned": False}
        if hit is not None:
            data["contacts"] = self._contact(hit)
            return False, data, f"pick path blocked by {hit}"
        if not done:
            return False, data, "stopped before the pick configuration"
        box = self.objects.get(obj)
        reason = ""
        if box is None:
            reason = f"{obj} is not there"
        elif box.center.dist(self._aim(obj, m)) > self.noise.grasp_tol:
            reason = f"{obj} is not where it was expected"
            data["missed"] = True
        elif self.noise.grasp_fail and self.rng.random() < self.noise.grasp_fail:
            reason = "the grasp slipped"
        if reason:
            back, hit2, done2 = self._follow(tuple(reversed(m.pick_path)))
            data["returned"] = done2
            data["back"] = back  # odometry of the way back, also when it stopped early
            return False, data, reason
        assert box is not None
        self.held = obj
        self.grip = np.array([box.cx - self.robot[0], box.cy - self.robot[1]])
        data["grasped"] = True
        return True, data, ""

    def _aim(self, obj: str, m: Manip) -> Pt:
        if self.grasp_estimate is not None:
            est = self.grasp_estimate(obj)
            if est is not None:
                return est
        return m.obj_at

    def _do_Place(self, obj: str, region: Region, ex: Any, exo: Any, m: Manip, home: Pt, pc: Pt,
                  place: Box, spot: Region, only: Any, survey: Region, keep: Any = ()) -> tuple[bool, dict[str, Any], str]:
        data: dict[str, Any] = {"carried": 0.0, "returned": 0.0, "home": False}
        if self.held != obj:
            return False, data, f"not holding {obj}"
        carried, hit, done = self._follow(m.carry_path, carrying=obj)
        data["carried"] = carried
        box = self.objects[obj]
        if done:
            s = self.noise.place_sigma
            box = box.moved(Pt(box.cx + self.rng.gauss(0, s), box.cy + self.rng.gauss(0, s)))
            if self.box_hits(box, obj) is None:
                self.objects[obj] = box
        self.held = None
        if hit is not None:
            data["contacts"] = self._contact(hit)
            return False, data, f"dragging {obj} blocked by {hit}"
        if not done:
            return False, data, "dragging stopped early"
        self.drives += len(m.return_path) > 1
        back, hit, home_ok = self._follow(m.return_path)
        data["returned"] = back
        data["home"] = home_ok
        if hit is not None:
            data["contacts"] = self._contact(hit)
            return False, data, f"return path blocked by {hit}"
        if not home_ok:
            return False, data, "return stopped early"
        self._jitter_end(back)
        return True, data, ""
