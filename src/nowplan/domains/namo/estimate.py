"""A detected object's Gaussian position estimate, and the confidence multiplier ``k_of``.

:class:`ObjectEstimate` is one object's Kalman filter state (mean, 2x2
covariance, size) in :class:`nowplan.domains.namo.belief.NamoBelief`;
:func:`k_of` turns a failure probability into standard deviations, which
the belief fluents and generators use to grow an estimate's box.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from statistics import NormalDist

import numpy as np

from nowplan.domains.namo.geometry import Box, Pt


@lru_cache(maxsize=64)
def k_of(eps: float) -> float:
    """Standard deviations within which a Gaussian lies with probability 1 - eps (one-sided)."""
    return NormalDist().inv_cdf(1.0 - min(max(eps, 1e-6), 0.5))


@dataclass
class ObjectEstimate:
    name: str
    mean: np.ndarray
    cov: np.ndarray
    size: tuple[float, float]
    first_seen: int  # the belief's percept counter when it was first detected
    looks: int = 1

    @property
    def sigma(self) -> float:
        return float(math.sqrt(max(np.linalg.eigvalsh(self.cov).max(), 0.0)))

    @property
    def center(self) -> Pt:
        return Pt.of(self.mean[0], self.mean[1])

    @property
    def box(self) -> Box:
        return Box(float(self.mean[0]), float(self.mean[1]), self.size[0], self.size[1])

