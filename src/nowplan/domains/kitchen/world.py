"""The true kitchen: a PyBullet DIRECT scene the agent never reads, only observes.

Actions change the simulated state; ``detect`` casts rays (``rayTestBatch``)
from the fixed camera to five points on the top of every object: an object
is visible when some ray's first hit is that object (the robot is
transparent to the camera), is then missed with probability ``p_FN``, and
otherwise reported at its true position plus Gaussian noise.  ``pick``
fails when the object is not within 3 cm of where the agent expected it.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING, Any

import numpy as np

from nowplan.belief.particles import SensorModel
from nowplan.core.operators import Action
from nowplan.domains.kitchen import scene as S
from nowplan.worlds.base import Observation

if TYPE_CHECKING:
    from nowplan.domains.kitchen.belief import KitchenBelief

log = logging.getLogger(__name__)


class KitchenWorld:
    def __init__(self, placements: dict[str, tuple[str, tuple[float, float]]], seed: int,
                 sensor: SensorModel = SensorModel(), cabinet: bool = False) -> None:
        self.rng = np.random.default_rng(seed + 7919)
        self.sensor = sensor
        self.cabinet = cabinet
        self.scene = S.build(tuple(placements), cabinet)
        self.frames: dict[str, str] = {}
        self.rel: dict[str, np.ndarray] = {}
        for o, (frame, (x, y)) in placements.items():
            self.frames[o] = frame
            self.rel[o] = np.array([x, y, S.SIZES[o][2]])
        self.drawers = {d: 0.0 for d in S.containers(cabinet)}
        self.conf: tuple[float, ...] = S.HOME
        self.held: str | None = None
        self.stove_on = False
        self.cooked: set[str] = set()
        self.failure_prob = 0.0  # an action does nothing and reports failure (nowplan run --failure-prob)
        self.failures = 0
        self.sync()

    def set_faults(self, *, failure_prob: float | None = None, exogenous_prob: float | None = None) -> None:
        """``nowplan run --failure-prob``: with this probability an action does nothing and reports
        failure (the robot's configuration and the drawers are still reported)."""
        if exogenous_prob:
            raise ValueError("the kitchen world makes no exogenous changes; drop the exogenous probability")
        if failure_prob is not None:
            if not 0.0 <= failure_prob <= 1.0:
                raise ValueError(f"failure_prob must be in [0, 1], got {failure_prob}")
            self.failure_prob = failure_prob

    def true_state(self) -> KitchenBelief:
        """The kitchen as a belief with perfect knowledge, for judging the goal at the end of a run:
        one particle per object at its true pose, the true configuration, drawers, hand and stove.
        It shares the world's scene (the goal's fluents never move it; ``sync`` restores it)."""
        from nowplan.belief.particles import PoseParticles
        from nowplan.domains.kitchen.belief import Conf, KitchenBelief

        b = KitchenBelief({}, seed=0, sensor=self.sensor, scene=self.scene, cabinet=self.cabinet)
        b.objects = tuple(self.frames)
        b.particles = {o: PoseParticles.point(self.frames[o], tuple(float(v) for v in self.rel[o]))  # type: ignore[arg-type]
                       for o in self.frames}
        b.conf, b.drawers, b.held = Conf(tuple(self.conf)), dict(self.drawers), self.held
        b.stove_on, b.cooked = self.stove_on, set(self.cooked)
        return b

    def world_pos(self, o: str) -> np.ndarray:
        if self.frames[o] == "hand":
            S.set_conf(self.scene, self.conf)
            held: np.ndarray = S.ee_position(self.scene) - np.array([0.0, 0.0, S.SIZES[o][2] - 0.02])
            return held
        at: np.ndarray = S.frame_origin(self.frames[o], self.drawers) + self.rel[o]
        return at

    def sync(self) -> None:
        S.set_conf(self.scene, self.conf)
        for d, q in self.drawers.items():
            S.set_drawer(self.scene, d, q)
        for o in self.frames:
            S.set_object(self.scene, o, self.world_pos(o))

    def detect(self) -> tuple[dict[str, list[float] | None], dict[str, str]]:
        self.sync()
        p = self.scene.p
        out: dict[str, list[float] | None] = {}
        frames: dict[str, str] = {}
        for o, body in self.scene.objects.items():
            if o == self.held:
                continue
            c = self.world_pos(o)
            hx, hy, hz = S.SIZES[o]
            pts = [c + np.array([dx * hx * 0.6, dy * hy * 0.6, hz - 0.002])
                   for dx, dy in ((0, 0), (1, 1), (1, -1), (-1, 1), (-1, -1))]
            starts = [tuple(S.CAMERA)] * len(pts)
            ends = [tuple(c + (q - c) + (q - S.CAMERA) * 0.001) for q in pts]
            hits = self._ray_hits(starts, ends)
            visible = any(h == body for h in hits)
            if visible and self.rng.random() >= self.sensor.p_fn:
                out[o] = [float(v) for v in c + self.rng.normal(0.0, self.sensor.sigma, 3) * np.array([1, 1, 0])]
                frames[o] = self.frames[o]
            else:
                out[o] = None
        return out, frames

    def _ray_hits(self, starts: list[Any], ends: list[Any]) -> list[int]:
        """First body hit by each ray, looking through the robot."""
        p, c = self.scene.p, self.scene.client
        res = []
        for s, e in zip(starts, ends, strict=True):
            a = np.array(s)
            hit = -1
            for _ in range(6):
                r = p.rayTest(tuple(a), e, physicsClientId=c)[0]
                hit = r[0]
                if hit != self.scene.robot:
                    break
                d = np.array(e) - a
                a = np.array(r[3]) + d / np.linalg.norm(d) * 0.005
            res.append(hit)
        return res

    def execute(self, action: Action) -> Observation:
        a: tuple[Any, ...] = action.args
        name = action.name
        ok, reason = True, ""
        info: dict[str, Any] = {}
        if self.failure_prob and self.rng.random() < self.failure_prob:
            ok, reason, name = False, "injected failure", ""  # the action does nothing
            self.failures += 1
        if name == "move":
            self.conf = tuple(a[0].q)
        elif name in ("pull", "push"):
            d = str(a[0])
            self.drawers[d] = (S.CABINET_OPEN if d == S.CABINET else S.DRAWER_OPEN) if name == "pull" else 0.0
            self.conf = S.HOME  # the arm retracts after moving the handle
        elif name in ("pick", "pick_tall"):
            o, pose = str(a[0]), a[1]
            expected = S.frame_origin(pose.frame, self.drawers) + pose.rel()
            if self.frames[o] != pose.frame or np.linalg.norm(self.world_pos(o)[:2] - expected[:2]) > 0.03:
                ok, reason = False, f"{o} is not where it was believed to be"
            else:
                self.frames[o], self.rel[o], self.held = "hand", np.zeros(3), o
        elif name in ("place", "place_aside"):
            o, pose = str(a[0]), a[1]
            self.frames[o], self.rel[o], self.held = pose.frame, pose.rel(), None
        elif name == "cook":
            self.stove_on = True
            for o, f in self.frames.items():
                if f == "stove":
                    self.cooked.add(o)
        elif name == "stove_off":
            self.stove_on = False
        elif name == "detect":
            det, frames = self.detect()
            info["detections"] = det
            info["frames"] = frames
            info["seen"] = sorted(o for o, z in det.items() if z is not None)
        info["drawers"] = dict(self.drawers)
        info["conf"] = list(self.conf)
        if reason:
            info["reason"] = reason
        self.sync()
        return Observation(ok, None, (), info)
