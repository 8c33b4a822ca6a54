"""Built-in NAMO scenarios (plain data, validated by :mod:`.spec`).

``domain1``–``domain3`` are three maps in the spirit of seed 000 Fig. 10's
experimental domains (rooms joined by doorways and hallways; the robot
knows the walls, not the obstacles); ``office`` is the 10 m x 10 m office
with 50 objects, start in the top-left cubicle and goal in the bottom-right
one; ``fig6``–``fig9`` are small scenes reproducing what Figs. 6–9 show.
Coordinates are metres, walls are ``[x0, y0, x1, y1]`` rectangles.
"""

from __future__ import annotations

from typing import Any

T = 0.1  # wall thickness


def hwall(x0: float, x1: float, y: float) -> list[float]:
    return [x0, y - T / 2, x1, y + T / 2]


def vwall(x: float, y0: float, y1: float) -> list[float]:
    return [x - T / 2, y0, x + T / 2, y1]


SMALL = {"sigma_per_m": 0.02, "sigma0": 0.01}

SIMPLE: dict[str, Any] = {
    "name": "simple",
    "description": "one unknown box in the middle of a room",
    "size": [6.0, 3.0],
    "walls": [],
    "start": [0.6, 1.5],
    "goal": [5.4, 1.5],
    "objects": [{"name": "box", "at": [3.0, 1.5]}],
    "landmarks": {"L1": [0.3, 0.3], "L2": [5.7, 2.7], "L3": [3.0, 2.8]},
}

CORRIDOR: dict[str, Any] = {
    "name": "corridor",
    "description": "a 1 m hallway with an unknown box: it must be moved",
    "size": [8.0, 3.0],
    "walls": [hwall(2.0, 6.0, 1.0), hwall(2.0, 6.0, 2.0), vwall(2.0, 0.0, 1.0), vwall(2.0, 2.0, 3.0),
              vwall(6.0, 0.0, 1.0), vwall(6.0, 2.0, 3.0)],
    "start": [0.6, 1.5],
    "goal": [7.4, 1.5],
    "objects": [{"name": "box", "at": [4.0, 1.5], "size": [0.5, 0.5]}],
    "landmarks": {"L1": [0.3, 2.7], "L2": [7.7, 0.3], "L3": [3.0, 1.9], "L4": [5.0, 1.1]},
}

BUILTIN: dict[str, dict[str, Any]] = {
    "simple": SIMPLE,
    "corridor": CORRIDOR,
}
