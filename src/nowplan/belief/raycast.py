"""Analytic ray casts against axis-aligned boxes (the planner's occlusion model).

``segment_blocked(a, b, centres, half)`` says, for every box (centre, half
extents), whether the open segment from ``a`` to ``b`` passes through it
(slab test, vectorised over boxes).  The kitchen's belief uses it to ask
whether object *j* at a particle pose blocks the camera's line of sight to
object *i* at a particle pose (``B^i_j(x_i, x_j)`` of seed 004 V-B).
"""

from __future__ import annotations

import numpy as np


def segment_blocked(
    a: np.ndarray, b: np.ndarray, centres: np.ndarray, half: np.ndarray, eps: float = 1e-6
) -> np.ndarray:
    """For each box, does the segment ``a→b`` (excluding its last ``eps``) cross it?"""
    a = np.asarray(a, dtype=float)
    d = np.asarray(b, dtype=float) - a
    centres = np.atleast_2d(np.asarray(centres, dtype=float))
    half = np.broadcast_to(np.asarray(half, dtype=float), centres.shape)
    lo, hi = centres - half, centres + half
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = np.where(np.abs(d) > 1e-12, 1.0 / d, np.inf)
        t1 = (lo - a) * inv
        t2 = (hi - a) * inv
    tmin = np.minimum(t1, t2)
    tmax = np.maximum(t1, t2)
    # axes parallel to the segment: inside the slab or not at all
    par = np.abs(d) <= 1e-12
    inside = (a >= lo) & (a <= hi)
    tmin = np.where(par, np.where(inside, -np.inf, np.inf), tmin)
    tmax = np.where(par, np.where(inside, np.inf, -np.inf), tmax)
    enter = np.max(tmin, axis=1)
    leave = np.min(tmax, axis=1)
    end = 1.0 - eps / max(float(np.linalg.norm(d)), 1e-12)
    hit: np.ndarray = (enter <= leave) & (leave > 0.0) & (enter < end)
    return hit
