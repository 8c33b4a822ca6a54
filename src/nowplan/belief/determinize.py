"""Determinized costs of stochastic actions (seed 004 V).

*Self-loop determinization* (V-A): an action that succeeds with probability
at least ``p`` and otherwise returns to where it started at recovery cost
``c'`` costs, in expectation, ``ĉ = c + Σ_t c'(1−p)^t = c + c'/p − c'``.

For ``detect`` the success probability is bounded below (V-B, eq. 2) by

    P(Z^p_i) ≥ (1 − p_FN) · P(X_i ∈ 𝒳_i) · Π_{j≠i} L_j(𝒳_i) ≥ (1 − p_FN) · P(𝒳_i) · (1 − ε)^(n−1)

where 𝒳_i is a δ-neighbourhood of a sampled pose (the particles of *i*
within δ of it, i.e. where the density is positive), and
``L_j(𝒳_i) = inf_{x_i ∈ 𝒳_i} Σ_k w_k (1 − B^i_j(x_i, x^k_j))`` is the
worst-case probability, over 𝒳_i, that object *j* does not block the view.
The ε condition ``min_j L_j ≥ 1 − ε`` is what the derived ``BOccluded``
predicate tests: :func:`b_occluded` is true when some *j* violates it.

Other stochastic actions declare their success probability
(:class:`StochasticCost`), and a maximum expected cost ``c*``
(:class:`CostBound`) bounds the plans the policy accepts.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from nowplan.errors import ModelError

# B(x_i rows, x_j rows) -> (len(x_i), len(x_j)) booleans: does j at x_j block i at x_i?
BlockFn = Callable[[np.ndarray, np.ndarray], np.ndarray]


def self_loop_cost(c: float, c_fail: float, p: float) -> float:
    """``ĉ = c + c'/p − c'``; infinite when success is impossible (``p = 0``)."""
    if c < 0 or c_fail < 0:
        raise ModelError(f"costs must be non-negative, got c={c}, c'={c_fail}")
    if not 0.0 <= p <= 1.0:
        raise ModelError(f"a success probability must be in [0, 1], got {p}")
    if p <= 0.0:
        return math.inf
    return c + c_fail / p - c_fail


@dataclass(frozen=True)
class StochasticCost:
    """An action's declared cost ``c``, recovery cost ``c'`` and success probability ``p``."""

    cost: float
    recovery: float
    success: float

    @property
    def determinized(self) -> float:
        return self_loop_cost(self.cost, self.recovery, self.success)


@dataclass(frozen=True)
class CostBound:
    """The maximum expected cost ``c*`` a plan may have (seed 004 V)."""

    c_star: float = math.inf

    def admits(self, cost: float) -> bool:
        return cost <= self.c_star


def worst_case_visibility(
    targets: np.ndarray, blockers: np.ndarray, weights: np.ndarray, blocks: BlockFn
) -> float:
    """``L_j(𝒳_i)``: the least, over target poses, of the blocker's not-blocking mass."""
    targets = np.atleast_2d(targets)
    if len(targets) == 0:
        return 1.0
    b = np.asarray(blocks(targets, np.atleast_2d(blockers)), dtype=float)
    w = np.asarray(weights, dtype=float)
    w = w / w.sum()
    free = (1.0 - b) @ w  # per target pose
    return float(free.min())


def detection_lower_bound(p_fn: float, region_mass: float, visibilities: Sequence[float]) -> float:
    """Eq. (2) with the product of inequality (1): ``(1−p_FN)·P(𝒳_i)·Π_j L_j``."""
    return float((1.0 - p_fn) * region_mass * np.prod(np.asarray(visibilities, dtype=float)))


def epsilon_lower_bound(p_fn: float, region_mass: float, epsilon: float, n_objects: int) -> float:
    """Eq. (2) in its ε form: ``(1−p_FN)·P(𝒳_i)·(1−ε)^(n−1)``; valid when no j is BOccluding."""
    return float((1.0 - p_fn) * region_mass * (1.0 - epsilon) ** max(n_objects - 1, 0))


def b_occluded(visibilities: Sequence[float], epsilon: float) -> bool:
    """The derived ``BOccluded`` test: some other object blocks with probability above ε."""
    return any(v < 1.0 - epsilon for v in visibilities)
