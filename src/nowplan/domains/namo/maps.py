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
    "landmarks": {"L1": [0.3, 2.7], "L2": [7.7, 0.3], "L3": [3.0, 1.75], "L4": [5.0, 1.25]},
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
    "landmarks": {"L1": [0.2, 2.2], "L2": [3.6, 0.8], "L3": [7.8, 4.2], "L4": [7.8, 0.2]},
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
    "start": [0.8, 2.4],
    "goal": [8.2, 3.4],
    "objects": [
        {"name": "top", "at": [3.6, 5.05], "believed_at": [3.6, 4.65], "known": True, "sigma": 0.3},
        {"name": "bottom", "at": [5.0, 0.4], "known": True, "sigma": 0.03},
    ],
    "landmarks": {"L1": [0.2, 0.2], "L2": [0.2, 5.2], "L3": [8.8, 5.2], "L4": [8.8, 0.2], "L5": [5.0, 5.2]},
}

# -- seed 000 Fig. 10 in spirit: the three experimental domains and the office ---------------------

LM_GRID = {f"L{i}{j}": [0.3 + i * 3.1, 0.3 + j * 2.7] for i in range(4) for j in range(3)}

# Domain 1: two rooms, two doors; an unknown box in the nearer door, a chair on the way to it and a
# few more objects scattered in the rooms.
DOMAIN1: dict[str, Any] = {
    "name": "domain1",
    "description": "domain 1: two rooms joined by two doors",
    "size": [10.0, 6.0],
    "walls": [vwall(5.0, 0.0, 0.9), vwall(5.0, 2.1, 3.9), vwall(5.0, 5.1, 6.0)],
    "start": [1.0, 3.4],
    "goal": [9.0, 3.4],
    "objects": [
        {"name": "doorA", "at": [5.0, 4.5], "size": [0.5, 0.5], "jitter": 0.08},
        {"name": "chair", "at": [3.2, 3.9], "size": [0.45, 0.45], "jitter": 0.3},
    ],
    "scatter": [
        {"count": 2, "area": [0.5, 0.5, 4.4, 5.5], "prefix": "left"},
        {"count": 3, "area": [5.6, 0.5, 9.5, 5.5], "prefix": "right"},
    ],
    "landmarks": LM_GRID,
}

# Domain 2: three corridors through a block; the straight middle one holds a box, the others may
# hold scattered objects.
DOMAIN2: dict[str, Any] = {
    "name": "domain2",
    "description": "domain 2: three corridors through a block",
    "size": [10.0, 6.0],
    "walls": [[3.0, 1.7, 7.0, 2.5], [3.0, 3.5, 7.0, 4.3], [3.0, 5.4, 7.0, 6.0], [3.0, 0.0, 7.0, 0.5]],
    "start": [1.0, 3.0],
    "goal": [9.0, 3.0],
    "objects": [
        {"name": "midbox", "at": [5.0, 3.0], "size": [0.5, 0.5], "jitter": 1.2},
    ],
    "scatter": [
        {"count": 2, "area": [3.2, 0.6, 6.8, 1.6], "prefix": "low"},
        {"count": 1, "area": [3.2, 4.4, 6.8, 5.3], "prefix": "high"},
        {"count": 2, "area": [0.4, 0.4, 2.8, 5.6], "prefix": "west"},
        {"count": 2, "area": [7.2, 0.4, 9.6, 5.6], "prefix": "east"},
    ],
    "landmarks": {"L1": [0.3, 0.3], "L2": [0.3, 3.0], "L3": [0.3, 5.7], "L4": [5.0, 0.7], "L5": [5.0, 5.2],
                  "L6": [5.0, 2.6], "L7": [9.7, 0.3], "L8": [9.7, 3.0], "L9": [9.7, 5.7]},
}

# Domain 3: three rooms in a row; two doors into the middle room, a single door (holding a box)
# into the last one.
DOMAIN3: dict[str, Any] = {
    "name": "domain3",
    "description": "domain 3: three rooms in a row",
    "size": [12.0, 6.0],
    "walls": [vwall(4.0, 0.0, 0.6), vwall(4.0, 1.8, 4.2), vwall(4.0, 5.4, 6.0),
              vwall(8.0, 0.0, 2.4), vwall(8.0, 3.6, 6.0)],
    "start": [1.0, 3.0],
    "goal": [11.0, 3.0],
    "objects": [
        {"name": "door2", "at": [8.0, 3.0], "size": [0.5, 0.5], "jitter": 0.1},
        {"name": "chair", "at": [4.0, 4.8], "size": [0.45, 0.45], "jitter": 0.1},
    ],
    "scatter": [
        {"count": 2, "area": [0.5, 0.5, 3.6, 5.5], "prefix": "r1_"},
        {"count": 3, "area": [4.4, 0.5, 7.6, 5.5], "prefix": "r2_"},
        {"count": 2, "area": [8.4, 0.5, 11.5, 5.5], "prefix": "r3_"},
    ],
    "landmarks": {**LM_GRID, "L40": [11.7, 0.3], "L41": [11.7, 3.0], "L42": [11.7, 5.7]},
}


def _office_walls() -> list[list[float]]:
    walls: list[list[float]] = []
    # four quadrants of 2 x 2 cubicles, separated by a cross of aisles (x, y in [4.4, 5.6])
    for qx in (0.0, 5.6):
        for qy in (0.0, 5.6):
            for cx in (qx, qx + 2.2):
                for cy in (qy, qy + 2.2):
                    # a cubicle [cx, cx + 2.2] x [cy, cy + 2.2]: partitions with a 1.2 m opening
                    # facing the vertical aisle side
                    top, bottom = cy + 2.2, cy
                    if cy + 2.2 < 10.0 - 1e-9:
                        walls.append(hwall(cx + 0.2, cx + 2.0, top))
                    if cy > 1e-9 and abs(cy - 5.6) > 1e-9:
                        walls.append(hwall(cx + 0.2, cx + 2.0, bottom))
                    left = cx < 4.4
                    side = cx + 2.2 if left else cx
                    if abs(side - 2.2) < 1e-9 or abs(side - 7.8) < 1e-9:
                        walls.append(vwall(side, cy + 0.2, cy + 0.5))
                        walls.append(vwall(side, cy + 1.7, cy + 2.0))
    return walls


def _office_scatter() -> list[dict[str, Any]]:
    """48 objects (with the two chairs in doorways, 50): in each cubicle, three along its two long
    partitions, leaving a walkway through the middle (one in the start's and in the goal's cubicle);
    three in each aisle (the start and goal cubicles are too small for their share)."""
    out: list[dict[str, Any]] = []
    i = 0
    for qx in (0.0, 5.6):
        for qy in (0.0, 5.6):
            for cx in (qx, qx + 2.2):
                for cy in (qy, qy + 2.2):
                    mine = (cx, cy) in ((0.0, 7.8), (7.8, 0.0))  # start and goal cubicles
                    out.append({"count": 1 if mine else 2, "area": [cx + 0.35, cy + 0.38, cx + 1.85, cy + 0.42],
                                "size": [0.45, 0.45], "prefix": f"c{i}b", "clearance": 0.9})
                    if not mine:
                        out.append({"count": 1, "area": [cx + 0.35, cy + 1.78, cx + 1.85, cy + 1.82],
                                    "size": [0.45, 0.45], "prefix": f"c{i}t", "clearance": 0.9})
                    i += 1
    out.append({"count": 3, "area": [4.55, 0.3, 5.45, 9.7], "size": [0.45, 0.45], "prefix": "av", "clearance": 0.9})
    out.append({"count": 3, "area": [0.3, 4.55, 9.7, 5.45], "size": [0.45, 0.45], "prefix": "ah", "clearance": 0.9})
    return out


OFFICE: dict[str, Any] = {
    "name": "office",
    "description": "the 100 m2 office with 50 objects: top-left cubicle to bottom-right cubicle",
    "size": [10.0, 10.0],
    "walls": _office_walls(),
    "start": [1.0, 9.0],
    "goal": [9.0, 1.0],
    "objects": [
        {"name": "chair_a", "at": [2.2, 8.9], "size": [0.45, 0.45], "jitter": 0.15},
        {"name": "chair_b", "at": [7.8, 1.1], "size": [0.45, 0.45], "jitter": 0.15},
    ],
    "scatter": _office_scatter(),
    "landmarks": {f"L{i}{j}": [0.3 + i * 3.13, 0.3 + j * 3.13] for i in range(4) for j in range(4)},
    "max_actions": 600,
}

BUILTIN: dict[str, dict[str, Any]] = {
    "domain1": DOMAIN1,
    "domain2": DOMAIN2,
    "domain3": DOMAIN3,
    "office": OFFICE,
    "simple": SIMPLE,
    "corridor": CORRIDOR,
    "fig6": FIG6,
    "fig7": FIG7,
    "fig8": FIG8,
    "fig9": FIG9,
}
