"""A particle filter over one movable object's pose, relative to its frame (seed 004 III).

Each particle is a frame name (the counter, a drawer, the stove, the hand)
and a position relative to that frame, with a weight.  Frames themselves
move (a drawer slides), so world positions are computed from the frames'
current origins, which the caller supplies as point estimates.

The Bayesian update from one camera observation (seed 004 V-B's model):

* detected at ``z``:  ``w_i ∝ w_i · v_i · (1 − p_FN) · N(z; x_i, σ² I)``
* not detected:       ``w_i ∝ w_i · (1 − v_i · (1 − p_FN))`` (negative evidence)

where ``v_i`` is the probability that the object would be visible at
particle ``i``.  False positives are taken to be impossible (the paper's
conservative choice).  After an update the filter resamples (systematic
resampling, seeded) when the effective sample size drops below half, and
jitters resampled particles within their frame's support.  A detection far
from every particle (all likelihoods underflow) re-seeds the particles
around ``z``: the prior had no mass there, so nothing else is consistent.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np

from nowplan.errors import ModelError

log = logging.getLogger(__name__)

DEFAULT_PARTICLES = 100
ROUGHEN_K = 0.2  # Gordon, Salmond & Smith's roughening constant
RANGE_PER_STD = 4.0  # the spread E of a cloud in standard deviations (about ±2σ holds 95 %)


@dataclass(frozen=True)
class Region:
    """An axis-aligned support region of a frame, in frame coordinates (x, y at height z)."""

    frame: str
    lo: tuple[float, float]
    hi: tuple[float, float]
    z: float = 0.0

    def contains(self, xy: np.ndarray, margin: float = 1e-9) -> np.ndarray:
        out: np.ndarray = np.all((xy >= np.asarray(self.lo) - margin) & (xy <= np.asarray(self.hi) + margin), axis=-1)
        return out

    @property
    def area(self) -> float:
        return max(self.hi[0] - self.lo[0], 0.0) * max(self.hi[1] - self.lo[1], 0.0)


@dataclass(frozen=True)
class SensorModel:
    p_fn: float = 0.1  # false-negative probability given visibility
    sigma: float = 0.01  # std (m) of the observed position per axis

    def __post_init__(self) -> None:
        if not 0.0 <= self.p_fn < 1.0:
            raise ModelError(f"p_FN must be in [0, 1), got {self.p_fn}")
        if self.sigma <= 0:
            raise ModelError(f"pose noise sigma must be > 0, got {self.sigma}")


VisibilityFn = Callable[[np.ndarray, np.ndarray], np.ndarray]  # (frames, world xyz) -> P(visible)


def gaussian_density(z: np.ndarray, x: np.ndarray, sigma: float) -> np.ndarray:
    """Isotropic normal density ``N(z; x, σ² I)`` for each row of ``x``."""
    d = x.shape[-1]
    sq = np.sum((x - z) ** 2, axis=-1)
    out: np.ndarray = np.exp(-0.5 * sq / sigma**2) / ((2 * math.pi * sigma**2) ** (d / 2))
    return out


def detection_likelihood(
    visible: np.ndarray, sensor: SensorModel, z: np.ndarray | None, world: np.ndarray
) -> np.ndarray:
    """``P(observation | particle)`` for a detection at ``z`` or a miss (``z`` is None)."""
    p_det = visible * (1.0 - sensor.p_fn)
    if z is None:
        return 1.0 - p_det
    out: np.ndarray = p_det * gaussian_density(np.asarray(z, dtype=float), world, sensor.sigma)
    return out


class PoseParticles:
    """Weighted particles ``(frame, relative xyz)`` for one object."""

    def __init__(self, frames: np.ndarray, poses: np.ndarray, weights: np.ndarray | None = None) -> None:
        self.frames = np.asarray(frames, dtype=object)
        self.poses = np.asarray(poses, dtype=float).reshape(len(self.frames), 3)
        n = len(self.frames)
        if n == 0:
            raise ModelError("a particle belief needs at least one particle")
        w = np.full(n, 1.0 / n) if weights is None else np.asarray(weights, dtype=float)
        self.weights = w / w.sum()

    # -- construction ----------------------------------------------------------
    @staticmethod
    def uniform(regions: list[Region], n: int, rng: np.random.Generator) -> PoseParticles:
        """``n`` particles spread over ``regions`` in proportion to their areas."""
        if not regions:
            raise ModelError("a uniform prior needs at least one region")
        areas = np.array([max(r.area, 1e-12) for r in regions])
        which = rng.choice(len(regions), size=n, p=areas / areas.sum())
        frames = np.empty(n, dtype=object)
        poses = np.zeros((n, 3))
        for k, r in enumerate(regions):
            idx = np.flatnonzero(which == k)
            frames[idx] = r.frame
            poses[idx, 0] = rng.uniform(r.lo[0], r.hi[0], size=len(idx))
            poses[idx, 1] = rng.uniform(r.lo[1], r.hi[1], size=len(idx))
            poses[idx, 2] = r.z
        return PoseParticles(frames, poses)

    @staticmethod
    def point(frame: str, pose: tuple[float, float, float], n: int = 1) -> PoseParticles:
        frames = np.array([frame] * n, dtype=object)
        return PoseParticles(frames, np.tile(np.asarray(pose, dtype=float), (n, 1)))

    def copy(self) -> PoseParticles:
        return PoseParticles(self.frames.copy(), self.poses.copy(), self.weights.copy())

    def __len__(self) -> int:
        return len(self.frames)

    # -- queries -----------------------------------------------------------------
    def world(self, origins: Mapping[str, np.ndarray]) -> np.ndarray:
        """World positions given each frame's origin (point estimates)."""
        off = np.array([np.asarray(origins[f], dtype=float) for f in self.frames])
        out: np.ndarray = self.poses + off
        return out

    def frame_mass(self, frame: str) -> float:
        return float(self.weights[self.frames == frame].sum())

    def frame_masses(self) -> dict[str, float]:
        return {str(f): self.frame_mass(str(f)) for f in sorted(set(self.frames.tolist()))}

    def near(self, frame: str, rel: np.ndarray, delta: float) -> np.ndarray:
        """Mask of particles in ``frame`` within ``delta`` (xy) of ``rel``."""
        d = np.linalg.norm(self.poses[:, :2] - np.asarray(rel, dtype=float)[:2], axis=1)
        out: np.ndarray = (self.frames == frame) & (d <= delta)
        return out

    def mass_near(self, frame: str, rel: np.ndarray, delta: float) -> float:
        return float(self.weights[self.near(frame, rel, delta)].sum())

    def mode(self, delta: float) -> tuple[str, np.ndarray, float]:
        """The particle whose δ-neighbourhood holds the most mass: (frame, rel pose, mass)."""
        best = (str(self.frames[0]), self.poses[0], -1.0)
        for i in np.argsort(-self.weights)[: min(len(self), 50)]:
            m = self.mass_near(str(self.frames[i]), self.poses[i], delta)
            if m > best[2]:
                mask = self.near(str(self.frames[i]), self.poses[i], delta)
                centre = np.average(self.poses[mask], axis=0, weights=self.weights[mask])
                best = (str(self.frames[i]), centre, m)
        return best

    def ess(self) -> float:
        return float(1.0 / np.sum(self.weights**2))

    # -- updates -------------------------------------------------------------------
    def reweight(self, likelihood: np.ndarray) -> float:
        """Multiply weights by ``likelihood`` and normalise; returns the evidence ``Σ w·l``."""
        w = self.weights * np.asarray(likelihood, dtype=float)
        total = float(w.sum())
        if total > 0 and math.isfinite(total):
            self.weights = w / total
        return total

    def update(
        self,
        sensor: SensorModel,
        visibility: VisibilityFn,
        origins: Mapping[str, np.ndarray],
        z: np.ndarray | None,
        rng: np.random.Generator,
        supports: Mapping[str, Region] | None = None,
        z_frame: str | None = None,
    ) -> float:
        """Bayesian update from one observation (``z`` world position, or None = not seen)."""
        world = self.world(origins)
        vis = np.clip(visibility(self.frames, world), 0.0, 1.0)
        evidence = self.reweight(detection_likelihood(vis, sensor, z, world))
        if z is not None and not evidence > 1e-300:
            if z_frame is None:
                raise ModelError("a detection with no supporting particle needs the frame it lies in")
            log.info("detection far from every particle: re-seeding around it")
            rel = np.asarray(z, dtype=float) - np.asarray(origins[z_frame], dtype=float)
            n = len(self)
            self.frames = np.array([z_frame] * n, dtype=object)
            self.poses = rel + rng.normal(0.0, sensor.sigma, size=(n, 3)) * np.array([1, 1, 0])
            self.weights = np.full(n, 1.0 / n)
            return 0.0
        if self.ess() < len(self) / 2:
            self.resample(rng, jitter=self.roughening(sensor), supports=supports)
        return evidence

    def roughening(self, sensor: SensorModel) -> float:
        """The xy jitter of a resampling after an update: Gordon et al.'s roughening, ``K·E·N^(-1/d)``
        (``E`` the spread of the weighted cloud, ``d`` = 2, ``K`` = ``ROUGHEN_K``), at most half the
        sensor's noise.

        A jitter of half the sensor's noise, whatever the cloud's spread, put a floor under the
        spread that repeated looks could not go below: with σ = 0.03 m about 0.024 m per axis, where
        ``localized`` needs about 0.009 m, so a kitchen look was planned again and again (cook,
        sensor sigma 0.03: 19 looks in 40 actions, the block never localised).  Proportional to the
        spread, the floor is about ``K·N^(-1/2)`` of the noise."""
        w = self.weights
        xy = self.poses[:, :2]
        mean = w @ xy
        spread = float(np.sqrt(max(float(w @ ((xy - mean) ** 2).sum(axis=1)), 0.0)))
        frames = set(self.frames.tolist())
        if len(frames) > 1:  # poses in different frames are not comparable: keep the sensor's bound
            return sensor.sigma / 2
        e = RANGE_PER_STD * spread
        return float(min(sensor.sigma / 2, ROUGHEN_K * e * len(self) ** -0.5))

    def resample(
        self, rng: np.random.Generator, jitter: float = 0.0, supports: Mapping[str, Region] | None = None
    ) -> None:
        """Systematic resampling; optional xy jitter kept inside each frame's support."""
        n = len(self)
        positions = (rng.random() + np.arange(n)) / n
        cum = np.cumsum(self.weights)
        cum[-1] = 1.0
        idx = np.searchsorted(cum, positions)
        frames, poses = self.frames[idx].copy(), self.poses[idx].copy()
        if jitter > 0:
            moved = poses.copy()
            moved[:, :2] += rng.normal(0.0, jitter, size=(n, 2))
            if supports:
                for i, f in enumerate(frames):
                    r = supports.get(str(f))
                    if r is not None and not r.contains(moved[i, :2]):
                        moved[i] = poses[i]
            poses = moved
        self.frames, self.poses, self.weights = frames, poses, np.full(n, 1.0 / n)

    def move_frame(self, old: str, new: str, offset: np.ndarray) -> None:
        """Re-attach every particle of ``old`` to ``new``, shifting by ``offset``."""
        mask = self.frames == old
        self.frames[mask] = new
        self.poses[mask] += np.asarray(offset, dtype=float)

    def __repr__(self) -> str:
        masses = ", ".join(f"{f}={m:.2f}" for f, m in self.frame_masses().items())
        return f"PoseParticles(n={len(self)}, {masses})"
