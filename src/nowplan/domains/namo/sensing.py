"""The NAMO belief's sensing updates: the robot's pose from landmarks, objects from detections.

The robot's position is a Gaussian with an isotropic variance; looking at a landmark is a Kalman
update of it (:func:`localise`).  Every detected object has a 2x2 Gaussian estimate updated by a
Kalman filter from a relative measurement whose noise adds the robot's own variance
(:func:`detect`); an estimate that lands inside a wall is moved to the nearest clear position
(:func:`off_walls`); an object that should have been seen where it was believed to be and was
not is dropped (negative information, in :func:`sense`).
"""

from __future__ import annotations

import logging
import math
from typing import TYPE_CHECKING, Any

import numpy as np

from nowplan.domains.namo.estimate import ObjectEstimate
from nowplan.domains.namo.geometry import Pt

if TYPE_CHECKING:
    from nowplan.domains.namo.belief import NamoBelief

log = logging.getLogger(__name__)


def sense(b: NamoBelief, data: dict[str, Any]) -> None:
    """Fold an observation's ``data`` into ``b``: cells seen, a bump, landmarks, detections and contacts."""
    g = b.geom.grid
    rc = g.cell(b.pose)
    ri, rj = g.ij(rc)
    visible = data.get("visible")
    seen_cells = np.zeros(0, dtype=int)
    if visible is not None and len(visible):
        rel = np.asarray(visible, dtype=int).reshape(-1, 2)
        ii, jj = rel[:, 0] + ri, rel[:, 1] + rj
        ok = (ii >= 0) & (ii < g.nx) & (jj >= 0) & (jj < g.ny)
        seen_cells = jj[ok] * g.nx + ii[ok]
        b.observed[seen_cells] = True
    b.observed |= g.disk_mask(b.pose, 0.5)
    bump = data.get("bump")
    if bump is not None:  # the robot cannot stand there: keep paths off that spot
        b.bumps.add(g.cell(Pt.of(b.robot_mean[0] + bump[0], b.robot_mean[1] + bump[1])))
    for lm, rx, ry, s in data.get("landmarks", ()):
        localise(b, b.geom.landmark(lm), float(rx), float(ry), float(s))
    detected = set()
    for name, rx, ry, s, w, h in [*data.get("detections", ()), *data.get("contacts", ())]:
        detected.add(name)
        detect(b, name, float(rx), float(ry), float(s), (float(w), float(h)))
    if seen_cells.size:
        seen = set(seen_cells.tolist())
        for o in b.free_objects():
            if o.name not in detected and g.cell(o.center) in seen and o.sigma < 0.15:
                log.info("object %s not seen where believed: dropped", o.name)
                del b.objects[o.name]
                b.percept += 1


def localise(b: NamoBelief, lm: Pt, rx: float, ry: float, s: float) -> None:
    """A Kalman update of the robot's position from landmark ``lm`` seen at ``(rx, ry)`` with noise ``s``."""
    z = np.array([lm.x - rx, lm.y - ry])
    r = s * s
    k = b.robot_var / (b.robot_var + r)
    b.robot_mean = b.robot_mean + k * (z - b.robot_mean)
    b.robot_var = (1 - k) * b.robot_var


def detect(b: NamoBelief, name: str, rx: float, ry: float, s: float, size: tuple[float, float]) -> None:
    """A Kalman update of ``name``'s estimate (a new one if unknown) from a detection at ``(rx, ry)``."""
    b.version += 1  # (update() bumps it again at the end; this keeps direct calls honest)
    z = b.robot_mean + np.array([rx, ry])
    R = np.eye(2) * (s * s + b.robot_var)
    est = b.objects.get(name)
    if name == b.held:
        return
    if est is None:
        b.percept += 1
        b.objects[name] = est = ObjectEstimate(name, z, R, size, b.percept)
        off_walls(b, est)
        log.info("new object %s at %s", name, est.center)
        return
    before_sigma, before_mean = est.sigma, est.mean.copy()
    S = est.cov + R
    K = est.cov @ np.linalg.inv(S)
    est.mean = est.mean + K @ (z - est.mean)
    est.cov = (np.eye(2) - K) @ est.cov
    est.looks += 1
    off_walls(b, est)
    if est.sigma < 0.7 * before_sigma or float(np.hypot(*(est.mean - before_mean))) > 0.2:
        b.percept += 1


def off_walls(b: NamoBelief, est: ObjectEstimate) -> None:
    """Objects cannot be inside walls: move the estimate to the nearest position clear of them."""
    w = np.array(b.geom.walls, dtype=float).reshape(-1, 4)
    if not len(w):
        return
    hw, hh = est.size[0] / 2 - 0.01, est.size[1] / 2 - 0.01

    def clear(x: float, y: float) -> bool:
        return not bool(np.any((x - hw < w[:, 2]) & (x + hw > w[:, 0]) & (y - hh < w[:, 3]) & (y + hh > w[:, 1])))

    x, y = float(est.mean[0]), float(est.mean[1])
    if clear(x, y):
        return
    for r in np.arange(0.02, 0.6, 0.02):
        best = None
        for a in np.linspace(0, 2 * math.pi, 24, endpoint=False):
            cx, cy = x + r * math.cos(a), y + r * math.sin(a)
            if clear(cx, cy):
                best = (cx, cy)
                break
        if best is not None:
            est.mean = np.array(best)
            return


# a look that did not detect an object is given up on when a visible object would have been missed that
# many times in a row with at most this chance (the rest of the time it was not visible from there)
MISS_GIVE_UP = 0.1


def looks_to_give_up(miss_prob: float, chance: float = MISS_GIVE_UP) -> int:
    """Looks in a row from one view point that must miss an object before a look from there is futile:
    the least k with ``miss_prob ** k <= chance`` (1 for a sensor that never misses a visible object)."""
    if miss_prob <= chance:
        return 1
    return max(1, math.ceil(math.log(chance) / math.log(min(miss_prob, 0.99))))
