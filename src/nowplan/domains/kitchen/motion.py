"""Inverse kinematics and RRT-Connect for the Panda on its rail (checked in a PyBullet scene).

A configuration is ``(base x, 7 arm joints)``.  :func:`inverse_kinematics`
tries a few base positions near the target and PyBullet's damped
least-squares IK for a top-down grasp, keeping solutions that reach within
1 cm and collide with nothing.  :func:`rrt_connect` (Kuffner & LaValle) grows
two trees in configuration space with a seeded RNG and a bounded number of
iterations, extending by fixed steps and checking every edge at a fixed
resolution; it first tries the straight segment.
"""

from __future__ import annotations

import math
import random
from collections.abc import Sequence

import numpy as np

from nowplan.domains.kitchen.scene import ARM_JOINTS, EE_LINK, RAIL, Scene, ee_position, set_conf

Conf = tuple[float, ...]
DOWN = (1.0, 0.0, 0.0, 0.0)  # gripper pointing down (quaternion x, y, z, w)
DOWN_TURNED = (0.7071068, 0.7071068, 0.0, 0.0)  # pointing down, turned 90° about the vertical


def limits(sc: Scene) -> tuple[np.ndarray, np.ndarray]:
    lo, hi = [RAIL[0]], [RAIL[1]]
    for j in ARM_JOINTS:
        info = sc.p.getJointInfo(sc.robot, j, physicsClientId=sc.client)
        lo.append(info[8])
        hi.append(info[9])
    return np.array(lo), np.array(hi)


def in_collision(sc: Scene, q: Conf, ignore: Sequence[int] = ()) -> bool:
    set_conf(sc, q)
    p = sc.p
    lid = (sc.lid,) if sc.lid >= 0 else ()
    for body in (*sc.statics[:-1], sc.drawers, *lid, *sc.objects.values()):  # not the pedestal it stands on
        if body in ignore:
            continue
        if p.getClosestPoints(sc.robot, body, 0.0, physicsClientId=sc.client):
            return True
    return False


def touching(sc: Scene, q: Conf, bodies: Sequence[int]) -> list[int]:
    """Which of ``bodies`` the robot touches at ``q`` (an object being grasped or just released)."""
    set_conf(sc, q)
    return [b for b in bodies if sc.p.getClosestPoints(sc.robot, b, 0.0, physicsClientId=sc.client)]


def inverse_kinematics(
    sc: Scene, target: np.ndarray, rng: random.Random, ignore: Sequence[int] = (), attempts: int = 4,
    orientation: tuple[float, float, float, float] = DOWN,
) -> Conf | None:
    p = sc.p
    lo, hi = limits(sc)
    bases = [float(np.clip(target[0] + dx, *RAIL)) for dx in (0.0, -0.15, 0.15, 0.3, -0.3)][:attempts]
    for bx in bases:
        rest = [0.0, -0.3, 0.0, -2.2, 0.0, 2.0, 0.8]
        set_conf(sc, (bx, *rest))
        sol = p.calculateInverseKinematics(
            sc.robot, EE_LINK, tuple(float(v) for v in target), orientation, lowerLimits=list(lo[1:]),
            upperLimits=list(hi[1:]), jointRanges=list(hi[1:] - lo[1:]), restPoses=rest,
            maxNumIterations=200, residualThreshold=1e-4, physicsClientId=sc.client,
        )
        q = (bx, *(float(np.clip(v, lo[i + 1], hi[i + 1])) for i, v in enumerate(sol[:7])))
        set_conf(sc, q)
        if np.linalg.norm(ee_position(sc) - target) > 0.01:
            continue
        if not in_collision(sc, q, ignore):
            return tuple(round(v, 5) for v in q)
    return None


def _edge_free(sc: Scene, a: np.ndarray, b: np.ndarray, ignore: Sequence[int], res: float = 0.05) -> bool:
    n = max(int(math.ceil(float(np.max(np.abs(b - a))) / res)), 1)
    for k in range(1, n + 1):
        if in_collision(sc, tuple(a + (b - a) * k / n), ignore):
            return False
    return True


def rrt_connect(
    sc: Scene, start: Conf, goal: Conf, rng: random.Random, ignore: Sequence[int] = (),
    iterations: int = 300, step: float = 0.3,
) -> list[Conf] | None:
    """A collision-free path from ``start`` to ``goal``, or None within ``iterations``."""
    a, b = np.array(start, dtype=float), np.array(goal, dtype=float)
    if in_collision(sc, tuple(b), ignore):
        return None
    if _edge_free(sc, a, b, ignore):
        return [tuple(a), tuple(b)]
    lo, hi = limits(sc)
    trees: list[list[tuple[np.ndarray, int]]] = [[(a, -1)], [(b, -1)]]

    def nearest(tree: list[tuple[np.ndarray, int]], q: np.ndarray) -> int:
        return int(np.argmin([np.linalg.norm(n[0] - q) for n in tree]))

    def extend(tree: list[tuple[np.ndarray, int]], q: np.ndarray) -> int | None:
        i = nearest(tree, q)
        base = tree[i][0]
        d = q - base
        dist = float(np.linalg.norm(d))
        new = q if dist <= step else base + d * (step / dist)
        if not _edge_free(sc, base, new, ignore):
            return None
        tree.append((new, i))
        return len(tree) - 1

    def path(tree: list[tuple[np.ndarray, int]], i: int) -> list[np.ndarray]:
        out = []
        while i >= 0:
            out.append(tree[i][0])
            i = tree[i][1]
        return out

    for it in range(iterations):
        q_rand = np.array([rng.uniform(l_, h_) for l_, h_ in zip(lo, hi, strict=True)])
        t0, t1 = trees[it % 2], trees[1 - it % 2]
        i0 = extend(t0, q_rand)
        if i0 is None:
            continue
        target = t0[i0][0]
        while True:  # connect: greedily extend the other tree towards the new node
            i1 = extend(t1, target)
            if i1 is None:
                break
            if np.linalg.norm(t1[i1][0] - target) < 1e-9:
                p0, p1 = path(t0, i0), path(t1, i1)
                full = p0[::-1] + p1 if it % 2 == 0 else p1[::-1] + p0
                return [tuple(float(v) for v in q) for q in full]
    return None
