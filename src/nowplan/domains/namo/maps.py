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

# Fig. 6: a new obstacle in the planned path; reconsideration finds a detour, the original
# BHPN moves it out of the committed swept volume.
FIG6: dict[str, Any] = {
    "name": "fig6",
    "description": "Fig. 6: an unknown obstacle on the straight path through a foggy room",
    "size": [8.0, 3.2],
    "walls": [],
    "start": [0.6, 1.6],
    "goal": [7.4, 1.6],
    "objects": [{"name": "box", "at": [4.4, 1.6], "size": [0.6, 0.6]}],
    "landmarks": {"L1": [0.2, 0.2], "L2": [4.0, 3.0], "L3": [7.8, 0.2]},
}

# Fig. 7: two known boxes in a hallway, a closet below it.  The path is cut into a left and a
# right part; without foresight the first box is put just past the left part (into the right
# one) and moved twice; with foresight the whole swept volume is taboo and it goes to the closet.
FIG7: dict[str, Any] = {
    "name": "fig7",
    "description": "Fig. 7: placements with and without considering future goals",
    "size": [8.0, 4.4],
    "fog": False,
    "walls": [hwall(0.0, 6.4, 3.0), hwall(0.0, 3.2, 2.0), hwall(5.2, 6.4, 2.0),
              vwall(3.2, 0.4, 2.0), vwall(5.2, 0.4, 2.0), hwall(3.2, 5.2, 0.4),
              [0.0, 3.05, 6.4, 4.4], [0.0, 0.0, 3.15, 1.95], [5.25, 0.0, 6.4, 1.95]],
    "start": [0.5, 2.5],
    "goal": [7.5, 2.5],
    "objects": [
        {"name": "green", "at": [1.9, 2.5], "known": True, "sigma": 0.02},
        {"name": "box2", "at": [5.9, 2.5], "known": True, "sigma": 0.02},
    ],
    "params": {"segment": 3.5},
    "landmarks": {"L1": [0.2, 2.2], "L2": [3.6, 0.6], "L3": [7.8, 4.2], "L4": [7.8, 0.2]},
}

# Fig. 8: a dead-end corridor; the box must go behind the robot.  Just behind it the robot
# would be cut off from where it started (and from the goal): the placement must keep the
# release configuration connected to home, so the box goes to the alcove at the bottom left.
FIG8: dict[str, Any] = {
    "name": "fig8",
    "description": "Fig. 8: placements that keep the free space connected",
    "size": [6.4, 4.0],
    "fog": False,
    "walls": [hwall(0.0, 0.4, 2.0), hwall(2.4, 6.4, 2.0), hwall(0.0, 6.4, 3.0),
              vwall(0.4, 0.5, 2.0), vwall(2.4, 0.5, 2.0), hwall(0.4, 2.4, 0.5), vwall(6.0, 2.0, 3.0)],
    "start": [4.3, 2.5],
    "goal": [5.6, 2.5],
    "objects": [{"name": "box", "at": [5.0, 2.5], "known": True, "sigma": 0.02}],
    "landmarks": {"L1": [0.2, 2.8], "L2": [3.0, 2.8]},
}

# Fig. 9: two hallways, one obstacle in each; the one in the (shorter) top hallway is badly
# localised.  With foresight its shadow makes the bottom hallway look better; once a look
# localises it, selective reconsideration takes the shorter top path.
FIG9: dict[str, Any] = {
    "name": "fig9",
    "description": "Fig. 9: shadows of uncertain obstacles inform the choice of path",
    "size": [9.0, 5.4],
    "walls": [[3.0, 1.4, 7.0, 3.4]],
    "start": [1.0, 3.0],
    "goal": [8.2, 3.0],
    "objects": [
        {"name": "top", "at": [4.0, 5.05], "believed_at": [4.0, 4.65], "known": True, "sigma": 0.3},
        {"name": "bottom", "at": [5.0, 0.4], "known": True, "sigma": 0.03},
    ],
    "landmarks": {"L1": [0.2, 0.2], "L2": [0.2, 5.2], "L3": [8.8, 5.2], "L4": [8.8, 0.2], "L5": [5.0, 5.2]},
}

BUILTIN: dict[str, dict[str, Any]] = {
    "simple": SIMPLE,
    "corridor": CORRIDOR,
    "fig6": FIG6,
    "fig7": FIG7,
    "fig8": FIG8,
    "fig9": FIG9,
}
