"""Self-loop determinization and the visibility lower bound of seed 004 eq. (2)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from nowplan.belief.determinize import (
    CostBound,
    StochasticCost,
    b_occluded,
    detection_lower_bound,
    epsilon_lower_bound,
    self_loop_cost,
    worst_case_visibility,
)
from nowplan.belief.raycast import segment_blocked
from nowplan.errors import ModelError

CAMERA = np.array([0.0, -1.0, 1.0])
HALF = np.array([0.05, 0.05, 0.1])


def blocks(targets: np.ndarray, blockers: np.ndarray) -> np.ndarray:
    out = np.zeros((len(targets), len(blockers)), dtype=bool)
    for i, t in enumerate(targets):
        out[i] = segment_blocked(CAMERA, t, blockers, HALF)
    return out


def test_self_loop_cost() -> None:
    assert self_loop_cost(1.0, 2.0, 1.0) == 1.0
    assert self_loop_cost(1.0, 2.0, 0.5) == pytest.approx(1.0 + 4.0 - 2.0)
    # the series form sum_t c'(1-p)^t
    p, c, cf = 0.3, 2.0, 5.0
    series = c + sum(cf * (1 - p) ** t for t in range(1, 400))
    assert self_loop_cost(c, cf, p) == pytest.approx(series)
    assert math.isinf(self_loop_cost(1.0, 1.0, 0.0))
    assert StochasticCost(1.0, 1.0, 0.5).determinized == pytest.approx(2.0)
    assert CostBound(10.0).admits(9.9) and not CostBound(10.0).admits(10.1)
    with pytest.raises(ModelError):
        self_loop_cost(1.0, 1.0, 1.5)


def test_segment_blocked() -> None:
    box = np.array([[0.0, -0.5, 0.5]])
    assert segment_blocked(CAMERA, np.array([0.0, 0.0, 0.0]), box, HALF)[0]
    assert not segment_blocked(CAMERA, np.array([0.5, 0.0, 0.0]), box, HALF)[0]
    # a box behind the target does not block it
    assert not segment_blocked(CAMERA, np.array([0.0, -0.5, 0.5]), np.array([[0.0, 0.3, -0.3]]), HALF)[0]


@pytest.mark.parametrize("seed", [0, 1, 2, 3, 4])
def test_visibility_bound_never_exceeds_monte_carlo(seed: int) -> None:
    rng = np.random.default_rng(seed)
    p_fn = 0.1
    # target i: particles spread on a table; two blockers with uncertain positions in between
    target = np.column_stack([rng.uniform(-0.3, 0.3, 100), rng.uniform(0.0, 0.3, 100), np.zeros(100)])
    w_t = rng.uniform(0.5, 1.5, 100)
    w_t /= w_t.sum()
    blockers = []
    for _ in range(2):
        cx = rng.uniform(-0.3, 0.3)
        pts = np.column_stack([cx + rng.normal(0, 0.08, 60), rng.uniform(-0.3, -0.1, 60), np.full(60, 0.1)])
        blockers.append((pts, np.full(60, 1 / 60)))
    # the bound for a sampled delta-neighbourhood
    centre = target[rng.integers(100)]
    near = np.linalg.norm(target[:, :2] - centre[:2], axis=1) <= 0.1
    region = target[near]
    mass = float(w_t[near].sum())
    vis = [worst_case_visibility(region, b, w, blocks) for b, w in blockers]
    bound = detection_lower_bound(p_fn, mass, vis)
    eps = 1.0 - min(vis)
    assert epsilon_lower_bound(p_fn, mass, eps, 3) <= bound + 1e-12
    assert not b_occluded(vis, eps) and (min(vis) == 1.0 or b_occluded(vis, eps / 2))
    # Monte-Carlo estimate of the true detection probability (independent object beliefs)
    m = 4000
    xi = target[rng.choice(100, size=m, p=w_t)]
    seen = np.ones(m, dtype=bool)
    for pts, w in blockers:
        xj = pts[rng.choice(len(pts), size=m, p=w)]
        seen &= ~np.array([segment_blocked(CAMERA, xi[k], xj[k : k + 1], HALF)[0] for k in range(m)])
    detected = seen & (rng.random(m) > p_fn)
    est = detected.mean()
    se = math.sqrt(max(est * (1 - est), 1e-4) / m)
    assert bound <= est + 3 * se
