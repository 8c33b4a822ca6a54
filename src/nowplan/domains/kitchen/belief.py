"""The agent's belief in the kitchen: particles per object, point estimates for the rest.

Object poses are :class:`~nowplan.belief.particles.PoseParticles` relative to
their frames; the robot configuration, drawer positions, what the hand holds
and the stove's state are point estimates (seed 004 III).  Visibility for
the filter and for the determinized costs is the analytic ray cast from the
camera to an object's top centre against the other objects' boxes (at their
particles), with drawer contents visible only when that drawer is open (and,
for the bottom one, the top drawer closed).  The belief owns a model scene
(its own PyBullet client) for IK and collision checks, and the kitchen's
streams.
"""

from __future__ import annotations

import logging
import math
import random
from collections.abc import Hashable
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from nowplan.belief.determinize import epsilon_lower_bound, self_loop_cost, worst_case_visibility
from nowplan.belief.particles import DEFAULT_PARTICLES, PoseParticles, Region, SensorModel
from nowplan.core.operators import Action
from nowplan.errors import ModelError
from nowplan.domains.kitchen import scene as S
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)

DELTA = 0.04  # radius of the δ-neighbourhood of a sampled pose (m)
EPSILON = 0.1  # the ε of the BOccluded test
LOCALIZED = 0.9  # mass within δ for a pose to be believed
MIN_DETECT_P = 0.01  # detections less likely than this to succeed cost infinity
PICK_MISS_SPREAD = 0.03  # std (m) added to an object's particles when a pick finds it elsewhere


@dataclass(frozen=True, order=True)
class Pose:
    """A position relative to a frame (the box centre)."""

    frame: str
    x: float
    y: float
    z: float
    constant: ClassVar[bool] = False

    def rel(self) -> np.ndarray:
        return np.array([self.x, self.y, self.z])

    def __str__(self) -> str:
        return f"{self.frame}({self.x:.2f},{self.y:.2f})"


@dataclass(frozen=True)
class Conf:
    q: tuple[float, ...]
    constant: ClassVar[bool] = False

    def __str__(self) -> str:
        return f"q(x={self.q[0]:.2f})"


@dataclass(frozen=True)
class Traj:
    path: tuple[tuple[float, ...], ...]
    constant: ClassVar[bool] = False

    def __str__(self) -> str:
        return f"traj[{len(self.path)}]"


def pose_of(frame: str, rel: np.ndarray) -> Pose:
    return Pose(frame, round(float(rel[0]), 4), round(float(rel[1]), 4), round(float(rel[2]), 4))


def segments_blocked(a: np.ndarray, ends: np.ndarray, centres: np.ndarray, half: np.ndarray,
                     eps: float = 1e-6) -> np.ndarray:
    """``out[k, m]``: does the segment ``a → ends[k]`` (less its last ``eps``) cross box ``m``?

    :func:`nowplan.belief.raycast.segment_blocked`'s slab test, vectorised over
    the segments as well as the boxes (the same answers, one numpy pass).
    """
    a = np.asarray(a, dtype=float)
    d = np.asarray(ends, dtype=float) - a  # (K, 3)
    lo = np.asarray(centres, dtype=float) - half  # (M, 3)
    hi = np.asarray(centres, dtype=float) + half
    par = np.abs(d) <= 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(par, np.inf, 1.0 / np.where(par, 1.0, d))
        t1 = (lo[None, :, :] - a) * inv[:, None, :]
        t2 = (hi[None, :, :] - a) * inv[:, None, :]
    tmin, tmax = np.minimum(t1, t2), np.maximum(t1, t2)
    inside = (a >= lo) & (a <= hi)  # (M, 3)
    parb = par[:, None, :]
    tmin = np.where(parb, np.where(inside[None], -np.inf, np.inf), tmin)
    tmax = np.where(parb, np.where(inside[None], np.inf, -np.inf), tmax)
    enter, leave = tmin.max(axis=2), tmax.min(axis=2)
    end = 1.0 - eps / np.maximum(np.linalg.norm(d, axis=1), 1e-12)
    hit: np.ndarray = (enter <= leave) & (leave > 0.0) & (enter < end[:, None])
    return hit


FINDABLE_ROUNDS = 20  # redraws of a findable prior's hidden particles before they are dropped


def kitchen_hides(target: str, world: np.ndarray, drawers: dict[str, float], cabinet: bool) -> Any:
    """Per row of ``world`` (positions of ``target``'s base): does the kitchen itself (a drawer's front
    panel, the counter top, the cabinet's walls) cut the camera's ray to ``target``'s top, the
    containers being as in ``drawers``?"""
    centres = [np.array([0.0, S.FRONT_Y - 0.01 - drawers.get(d, 0.0), S.DRAWER_FLOOR[d] + 0.08]) for d in S.DRAWERS]
    halves = [np.array([0.22, 0.01, 0.12])] * len(S.DRAWERS)
    centres.append(np.array([0.0, 0.725, S.COUNTER_TOP - 0.02]))
    halves.append(np.array([0.25, 0.275, 0.02]))
    if cabinet:
        for c, h in S.cabinet_boxes(drawers.get(S.CABINET, 0.0)):
            centres.append(c)
            halves.append(h)
    ends = np.atleast_2d(world) + np.array([0.0, 0.0, S.SIZES[target][2] - 0.005])
    hidden = np.zeros(len(ends), dtype=bool)
    for c, h in zip(centres, halves, strict=True):
        hidden |= segments_blocked(S.CAMERA, ends, c[None, :], h)[:, 0]
    return hidden


class KitchenBelief:
    def __init__(self, priors: dict[str, list[Region]], seed: int, sensor: SensorModel = SensorModel(),
                 n: int = DEFAULT_PARTICLES, scene: S.Scene | None = None, cabinet: bool = False,
                 findable: bool = False) -> None:
        """``findable``: every object's prior is conditioned on the object being where the camera can
        see it once its container is open and nothing else stands in front (see :meth:`_findable_prior`);
        without it, mass in the front strip of a drawer's tray grows with every look that misses and
        no look can ever reduce it."""
        self.rng = np.random.default_rng(seed)
        self.prng = random.Random(seed)
        self.sensor = sensor
        self.objects = tuple(priors)
        self.particles: dict[str, PoseParticles] = {}
        for o, regs in priors.items():
            lifted = [Region(r.frame, r.lo, r.hi, S.SIZES[o][2]) for r in regs]
            self.particles[o] = PoseParticles.uniform(lifted, n, self.rng)
        self.conf = Conf(S.HOME)
        self.cabinet = cabinet
        self.containers = S.containers(cabinet)  # the frames that open and close
        self.frames = S.frames_of(cabinet)
        self.regions = S.regions(cabinet)
        self.drawers = {d: 0.0 for d in self.containers}  # drawers' travel and the cabinet lid's (m)
        self.held: str | None = None
        self.stove_on = False
        self.cooked: set[str] = set()
        self.scene = scene or S.build(self.objects, cabinet)
        self.streams: Any = None  # set by the model (nowplan.domains.kitchen.model)
        self.planning_heuristic: Any = None  # likewise (nowplan.domains.kitchen.heuristic.estimate)
        self.version = 0
        self._modes: dict[tuple[str, int], Pose] = {}
        self._queries: dict[tuple[Any, ...], Any] = {}  # memoised tests, keyed with the version
        if findable:
            for o, regs in priors.items():
                if any(r.frame in self.containers for r in regs):
                    self._findable_prior(o, [Region(r.frame, r.lo, r.hi, S.SIZES[o][2]) for r in regs])

    # -- geometry ------------------------------------------------------------------
    def origins(self) -> dict[str, np.ndarray]:
        out = {f: S.frame_origin(f, self.drawers) for f in self.frames}
        out["hand"] = np.zeros(3)
        return out

    def frame_visible(self, frame: str) -> bool:
        if frame == "hand":
            return False
        if frame in self.containers and self.drawers[frame] < 0.2:
            return False
        return not (frame == "bottom" and self.drawers["top"] > 0.05)

    def _top_point(self, o: str, world: np.ndarray) -> np.ndarray:
        top: np.ndarray = world + np.array([0.0, 0.0, S.SIZES[o][2] - 0.005])
        return top

    def blocks(self, target: str, blocker: str) -> Any:
        """``B(x_i rows, x_j rows)``: does ``blocker`` at ``x_j`` hide ``target`` at ``x_i``?"""
        half = np.array(S.SIZES[blocker])

        def fn(xi: np.ndarray, xj: np.ndarray) -> np.ndarray:
            return segments_blocked(S.CAMERA, np.atleast_2d(xi) + self._top_point(target, np.zeros(3)),
                                    np.atleast_2d(xj), half)

        return fn

    def world_of(self, o: str) -> np.ndarray:
        return self.particles[o].world(self.origins())

    def statically_hidden(self, target: str, world: np.ndarray, drawers: dict[str, float] | None = None) -> Any:
        """Per row of ``world``: is the camera's ray to ``target``'s top there cut by the kitchen itself
        (a drawer's front panel, the counter top)?  Near the front of an open drawer an object hides
        behind the drawer's front panel."""
        return kitchen_hides(target, world, drawers if drawers is not None else self.drawers, self.cabinet)

    def _findable_prior(self, o: str, regions: list[Region], rounds: int = FINDABLE_ROUNDS) -> None:
        """Condition ``o``'s prior on being findable: no particle where the kitchen itself hides it from
        the camera even with its container open (the front strip of a drawer's tray, behind the
        front panel).  Such particles are redrawn from the prior (at most ``rounds`` times), then dropped."""
        pb = self.particles[o]
        for _ in range(rounds):
            bad = self._unfindable(o, pb)
            if not bad.any():
                return
            fresh = PoseParticles.uniform(regions, int(bad.sum()), self.rng)
            pb.frames[bad], pb.poses[bad] = fresh.frames, fresh.poses
        bad = self._unfindable(o, pb)
        if bad.all():
            raise ModelError(f"the prior of {o} lies wholly where the camera cannot see it")
        pb.reweight(~bad)

    def _unfindable(self, o: str, pb: PoseParticles) -> np.ndarray:
        bad = np.zeros(len(pb), dtype=bool)
        for f in self.containers:
            idx = np.flatnonzero(pb.frames == f)
            if len(idx):
                state = {d: (S.CABINET_OPEN if d == S.CABINET else S.DRAWER_OPEN) if d == f else 0.0
                         for d in self.containers}
                bad[idx] = kitchen_hides(o, S.frame_origin(f, state) + pb.poses[idx], state, self.cabinet)
        return bad

    def visibility(self, target: str) -> Any:
        """P(visible | particle) for the filter: frame visibility times Π_j P(j does not block)."""

        def fn(frames: np.ndarray, world: np.ndarray) -> np.ndarray:
            v = np.array([1.0 if self.frame_visible(str(f)) else 0.0 for f in frames])
            v *= ~self.statically_hidden(target, world)
            for j in self.objects:
                if j == target or j == self.held:
                    continue
                pj = self.particles[j]
                b = self.blocks(target, j)(world, self.world_of(j))
                v *= (1.0 - b.astype(float)) @ pj.weights
            return v

        return fn

    # -- what the planner asks ------------------------------------------------------------
    def region_of(self, o: str, pose: Pose) -> np.ndarray:
        pb = self.particles[o]
        mask = pb.near(pose.frame, pose.rel(), DELTA)
        out: np.ndarray = (pb.world(self.origins())[mask] if mask.any()
                           else (S.frame_origin(pose.frame, self.drawers) + pose.rel())[None, :])
        return out

    def not_blocks(self, blocker: str, target: str, pose: Pose) -> bool:
        """``L_j(𝒳_i) ≥ 1 − ε`` for blocker j and the δ-neighbourhood of ``pose`` (memoised per version)."""
        if blocker == self.held or blocker == target:
            return True
        if pose.frame == "hand":
            return True
        key = ("nb", blocker, target, pose, self.version)
        got = self._queries.get(key)
        if got is None:
            pj = self.particles[blocker]
            region = self.region_of(target, pose)
            lj = worst_case_visibility(region, self.world_of(blocker), pj.weights, self.blocks(target, blocker))
            got = self._queries[key] = lj >= 1.0 - EPSILON
        return bool(got)

    def look_cost(self, o: str, pose: Pose) -> float:
        """The determinized cost of looking for ``o`` near ``pose`` (``detect``'s self-loop cost
        ``c + c'/p − c'`` with p the ε form of eq. (2), c = c' = 1); infinite below
        ``MIN_DETECT_P`` (the cost bound c*, applied per action)."""
        mass = self.particles[o].mass_near(pose.frame, pose.rel(), DELTA)
        prob = epsilon_lower_bound(self.sensor.p_fn, mass, EPSILON, len(self.objects))
        return self_loop_cost(1.0, 1.0, prob) if prob >= MIN_DETECT_P else math.inf

    def cheapest_look(self, o: str) -> float:
        """:meth:`look_cost` at ``o``'s most supported pose (memoised per version): no look at ``o``
        costs much less, as no δ-neighbourhood holds much more mass than the mode's."""
        key = ("look", o, self.version)
        got = self._queries.get(key)
        if got is None:
            got = self._queries[key] = self.look_cost(o, self.mode_pose(o))
        return float(got)

    def localized_at(self, o: str, pose: Pose) -> bool:
        if pose.frame == "hand":
            return self.held == o
        return self.particles[o].mass_near(pose.frame, pose.rel(), DELTA / 2) >= LOCALIZED

    def candidate_poses(self, o: str, frame: str | None, k: int = 4) -> list[Pose]:
        """Sampled poses of ``o`` (the centres of ?obs), best-supported first."""
        pb = self.particles[o]
        mask = np.ones(len(pb), dtype=bool) if frame is None else pb.frames == frame
        mask &= pb.frames != "hand"
        if not mask.any():
            return []
        w = pb.weights * mask
        idx = self.prng.choices(range(len(pb)), weights=list(w / w.sum()), k=3 * k)
        out: list[Pose] = []
        for i in idx:
            f, rel = str(pb.frames[i]), pb.poses[i]
            if any(q.frame == f and np.linalg.norm(q.rel()[:2] - rel[:2]) < DELTA for q in out):
                continue
            out.append(pose_of(f, rel))
        out.sort(key=lambda q: -pb.mass_near(q.frame, q.rel(), DELTA))
        return out[:k]

    def mode_pose(self, o: str) -> Pose:
        """The most supported pose of ``o`` (memoised until the belief's next update)."""
        key = (o, self.version)
        m = self._modes.get(key)
        if m is None:
            f, rel, _ = self.particles[o].mode(DELTA / 2)
            m = pose_of(f, rel)
            self._modes[key] = m
        return m

    def sync_scene(self, skip: tuple[str, ...] = (), drawers: dict[str, float] | None = None) -> None:
        """Put the model scene in the believed state (objects at their modes; ``drawers`` overrides)."""
        S.set_conf(self.scene, self.conf.q)
        state = drawers if drawers is not None else self.drawers
        for d, q in state.items():
            S.set_drawer(self.scene, d, q)
        origins = {f: S.frame_origin(f, state) for f in self.frames} | {"hand": np.zeros(3)}
        for o in self.objects:
            if o in skip or o == self.held:
                S.set_object(self.scene, o, np.array([0.0, -2.0, -1.0 - self.objects.index(o)]))
                continue
            p = self.mode_pose(o)
            S.set_object(self.scene, o, origins[p.frame] + p.rel())

    # -- the progress guard's view ------------------------------------------------------------
    def fingerprint(self) -> Hashable:
        """Which situation the agent is in, for the progress guard (:mod:`nowplan.acting.progress`).

        Per object: the mass in each frame (to 0.05) and the most supported pose (to ``DELTA``)
        with the mass near it (to 0.05), so that a detection that localises an object or finds it
        absent from where it was looked for changes it, while resampling's jitter does not; the
        robot's configuration (to 1 cm / 0.01 rad), the drawers (to 1 cm), what is held, the stove
        and what is cooked.
        """
        objs = []
        for o in self.objects:
            pb = self.particles[o]
            p = self.mode_pose(o)
            objs.append((o, tuple((f, round(m / 0.05)) for f, m in pb.frame_masses().items()),
                         p.frame, round(p.x / DELTA), round(p.y / DELTA),
                         round(pb.mass_near(p.frame, p.rel(), DELTA / 2) / 0.05)))
        return (tuple(round(v, 2) for v in self.conf.q), tuple(sorted((d, round(q, 2)) for d, q in self.drawers.items())),
                self.held, self.stove_on, frozenset(self.cooked), tuple(objs))

    # -- updates --------------------------------------------------------------------------
    def update(self, action: Action, obs: Observation) -> None:
        """Bayesian update after ``action``; bumps :attr:`version` (memoised queries are keyed by it)."""
        self.version += 1
        self._modes.clear()
        self._queries.clear()
        args: tuple[Any, ...] = action.args
        name = action.name
        info = obs.info or {}
        if "drawers" in info:
            self.drawers = dict(info["drawers"])
        if "conf" in info:
            self.conf = Conf(tuple(info["conf"]))
        if name == "detect":
            for o, z in info.get("detections", {}).items():
                if o == self.held:
                    continue
                zz = None if z is None else np.asarray(z, dtype=float)
                frame = None if z is None else str(info.get("frames", {}).get(o))
                self.particles[o].update(self.sensor, self.visibility(o), self.origins(), zz, self.rng,
                                         supports=None, z_frame=frame)
        elif name in ("pick", "pick_tall") and obs.success:
            self.held = str(args[0])
            self.particles[self.held] = PoseParticles.point("hand", (0.0, 0.0, 0.0), len(self.particles[self.held]))
        elif name in ("pick", "pick_tall") and not obs.success:
            # the object was not where it was believed to be: spread the belief so that it is looked for again
            pb = self.particles[str(args[0])]
            pb.poses = pb.poses + self.rng.normal(0.0, PICK_MISS_SPREAD, size=pb.poses.shape) * np.array([1, 1, 0])
        elif name in ("place", "place_aside") and obs.success:
            o, pose = str(args[0]), args[1]
            self.held = None
            n = len(self.particles[o])
            jitter = self.rng.normal(0.0, 0.003, size=(n, 3)) * np.array([1, 1, 0])
            self.particles[o] = PoseParticles(np.array([pose.frame] * n, dtype=object), pose.rel() + jitter)
        elif name == "cook" and obs.success:
            self.stove_on = True
            self.cooked.add(str(args[0]))
        elif name == "stove_off" and obs.success:
            self.stove_on = False
        self._modes.clear()

    def copy_summary(self) -> dict[str, Any]:
        return {o: self.particles[o].frame_masses() for o in self.objects}
