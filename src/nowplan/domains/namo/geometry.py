"""Plane geometry for NAMO: points, boxes, swept capsules, the map and its grid.

The map (walls and landmarks) is known in advance; shapely holds the wall
polygons, and everything the planner and the belief ask many times is
answered on an occupancy grid (cells of ``res`` metres, flat index
``k = j * nx + i`` with column ``i`` along x and row ``j`` along y).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from nowplan.errors import require


CLEARANCE = 0.03  # the planner keeps the robot this much further from walls than its radius (m)
GRAZE_OK = 0.02  # a swept volume may graze an object's (shadow) boundary by this much (m)


def shapely() -> Any:
    """The lazily imported shapely module (the ``namo`` extra)."""
    return require("shapely", "namo")


@dataclass(frozen=True, order=True)
class Pt:
    """A point in metres (rounded to the centimetre so equal poses hash equal)."""

    x: float
    y: float

    @staticmethod
    def of(x: float, y: float) -> Pt:
        return Pt(round(float(x), 2), round(float(y), 2))

    def dist(self, o: Pt) -> float:
        return math.hypot(self.x - o.x, self.y - o.y)

    def __str__(self) -> str:
        return f"({self.x:g},{self.y:g})"


@dataclass(frozen=True, order=True)
class Box:
    """An axis-aligned rectangle: centre and size (objects never rotate here)."""

    cx: float
    cy: float
    w: float
    h: float

    @property
    def center(self) -> Pt:
        return Pt.of(self.cx, self.cy)

    def moved(self, p: Pt) -> Box:
        return Box(p.x, p.y, self.w, self.h)

    @property
    def bounds(self) -> tuple[float, float, float, float]:
        return (self.cx - self.w / 2, self.cy - self.h / 2, self.cx + self.w / 2, self.cy + self.h / 2)

    def shape(self) -> Any:
        return shapely().box(*self.bounds)

    def distance_to_segment(self, a: Pt, b: Pt) -> float:
        """Distance between this rectangle and segment ``ab`` (0 if they meet)."""
        x0, y0, x1, y1 = self.bounds
        if _segment_hits_rect(a, b, x0, y0, x1, y1):
            return 0.0
        best = min(_point_segment(Pt(cx, cy), a, b) for cx, cy in ((x0, y0), (x0, y1), (x1, y0), (x1, y1)))
        for p in (a, b):
            dx = max(x0 - p.x, 0.0, p.x - x1)
            dy = max(y0 - p.y, 0.0, p.y - y1)
            best = min(best, math.hypot(dx, dy))
        return best


def _point_segment(p: Pt, a: Pt, b: Pt) -> float:
    dx, dy = b.x - a.x, b.y - a.y
    L2 = dx * dx + dy * dy
    t = 0.0 if L2 == 0 else max(0.0, min(1.0, ((p.x - a.x) * dx + (p.y - a.y) * dy) / L2))
    return math.hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy))


def _segment_hits_rect(a: Pt, b: Pt, x0: float, y0: float, x1: float, y1: float) -> bool:
    """Liang–Barsky clipping: does segment ab meet the rectangle?"""
    t0, t1 = 0.0, 1.0
    dx, dy = b.x - a.x, b.y - a.y
    for p, q in ((-dx, a.x - x0), (dx, x1 - a.x), (-dy, a.y - y0), (dy, y1 - a.y)):
        if p == 0:
            if q < 0:
                return False
            continue
        r = q / p
        if p < 0:
            t0 = max(t0, r)
        else:
            t1 = min(t1, r)
        if t0 > t1:
            return False
    return True


@dataclass(frozen=True, order=True)
class Region:
    """The volume the robot sweeps moving straight from ``start`` to ``end``: a capsule.

    ``view`` is where the region is meant to be observed from (the start of
    the move).  ``stamp`` and ``foresight`` record the belief's perception
    counter and the foresight switch when the region was generated; they are
    bookkeeping for reconsideration triggers and take no part in equality.
    """

    start: Pt
    end: Pt
    radius: float
    stamp: int = field(default=0, compare=False)
    foresight: bool = field(default=False, compare=False)

    @property
    def view(self) -> Pt:
        return self.start

    @property
    def length(self) -> float:
        return self.start.dist(self.end)

    @property
    def centroid(self) -> Pt:
        return Pt((self.start.x + self.end.x) / 2, (self.start.y + self.end.y) / 2)

    def hits_box(self, box: Box, grow: float = 0.0) -> bool:
        """Does the box (grown by ``grow``) meet the volume swept after leaving the start?

        The robot already stands at the start, so what touches only its
        starting footprint is not in the way of the move: moving away from, or
        along, something it stands next to stays possible.  Moving closer to
        something it already touches is not (it would push into it; the
        world's contact test says the same).
        """
        L = self.length
        reach = self.radius + grow - GRAZE_OK
        if L < 1e-9:
            return box.distance_to_segment(self.start, self.end) < reach
        t = min(self.radius, L / 2) / L
        a = Pt(self.start.x + (self.end.x - self.start.x) * t, self.start.y + (self.end.y - self.start.y) * t)
        if box.distance_to_segment(a, self.end) < reach:
            return True
        d0 = box.distance_to_segment(self.start, self.start)
        return d0 < self.radius - GRAZE_OK and box.distance_to_segment(self.start, self.end) < d0 - 1e-3

    def shape(self) -> Any:
        sh = shapely()
        if self.length < 1e-9:
            return sh.Point(self.start.x, self.start.y).buffer(self.radius)
        return sh.LineString([(self.start.x, self.start.y), (self.end.x, self.end.y)]).buffer(self.radius)

    def __str__(self) -> str:
        return f"sw{self.start}->{self.end}"


@dataclass(frozen=True)
class Grid:
    """A regular grid over ``[0, width] x [0, height]``."""

    width: float
    height: float
    res: float

    @property
    def nx(self) -> int:
        return int(math.ceil(self.width / self.res - 1e-9))

    @property
    def ny(self) -> int:
        return int(math.ceil(self.height / self.res - 1e-9))

    @property
    def n(self) -> int:
        return self.nx * self.ny

    def cell(self, p: Pt) -> int:
        i = min(max(int(p.x / self.res), 0), self.nx - 1)
        j = min(max(int(p.y / self.res), 0), self.ny - 1)
        return j * self.nx + i

    def ij(self, k: int) -> tuple[int, int]:
        return k % self.nx, k // self.nx

    def center(self, k: int) -> Pt:
        i, j = self.ij(k)
        return Pt.of((i + 0.5) * self.res, (j + 0.5) * self.res)

    def snap(self, p: Pt) -> Pt:
        return self.center(self.cell(p))

    @cached_property
    def xs(self) -> np.ndarray:
        return (np.arange(self.n) % self.nx + 0.5) * self.res

    @cached_property
    def ys(self) -> np.ndarray:
        return (np.arange(self.n) // self.nx + 0.5) * self.res

    def inside(self, p: Pt) -> bool:
        return 0.0 <= p.x < self.width and 0.0 <= p.y < self.height

    # -- rasterisation ---------------------------------------------------------
    def box_mask(self, box: Box, grow: float = 0.0) -> np.ndarray:
        """Cells whose centre lies within ``grow`` (plus half a cell) of the box."""
        x0, y0, x1, y1 = box.bounds
        g = grow + self.res / 2
        dx = np.maximum(np.maximum(x0 - self.xs, 0.0), self.xs - x1)
        dy = np.maximum(np.maximum(y0 - self.ys, 0.0), self.ys - y1)
        if grow <= 0:  # cells that overlap the box with positive area
            return (dx < self.res / 2 - 1e-9) & (dy < self.res / 2 - 1e-9)
        return np.hypot(dx, dy) <= g

    def capsule_mask(self, a: Pt, b: Pt, radius: float) -> np.ndarray:
        dx, dy = b.x - a.x, b.y - a.y
        L2 = dx * dx + dy * dy
        if L2 == 0:
            t = np.zeros(self.n)
        else:
            t = np.clip(((self.xs - a.x) * dx + (self.ys - a.y) * dy) / L2, 0.0, 1.0)
        return np.hypot(self.xs - (a.x + t * dx), self.ys - (a.y + t * dy)) <= radius

    def disk_mask(self, c: Pt, radius: float) -> np.ndarray:
        return np.hypot(self.xs - c.x, self.ys - c.y) <= radius

    def dilate(self, mask: np.ndarray, radius: float) -> np.ndarray:
        """Grow a mask by a disk of ``radius`` metres."""
        r = int(math.ceil(radius / self.res - 1e-9))
        if r <= 0:
            return mask.copy()
        m2 = mask.reshape(self.ny, self.nx)
        out = m2.copy()
        for di in range(-r, r + 1):
            for dj in range(-r, r + 1):
                if (di == 0 and dj == 0) or math.hypot(di, dj) * self.res > radius + 1e-9:
                    continue
                out |= _shift(m2, di, dj)
        return out.reshape(-1)

    # -- lines of sight ----------------------------------------------------------
    def line_cells(self, a: Pt, b: Pt) -> np.ndarray:
        """Cells met by segment ab (sampled every quarter cell)."""
        L = a.dist(b)
        n = max(2, int(L / (self.res / 4)) + 2)
        t = np.linspace(0.0, 1.0, n)
        x = np.clip(a.x + t * (b.x - a.x), 0, self.width - 1e-6)
        y = np.clip(a.y + t * (b.y - a.y), 0, self.height - 1e-6)
        ks = (y / self.res).astype(int) * self.nx + (x / self.res).astype(int)
        return np.unique(ks)

    def visible(
        self, origin: Pt, targets: np.ndarray, opaque: np.ndarray, max_range: float,
        heading: float | None = None, fov: float = 2 * math.pi,
    ) -> np.ndarray:
        """Which target cells are seen from ``origin``: in range, in the field of view, in line of sight.

        A cell is seen if no opaque cell lies strictly between it and the
        origin's cell (so the surface of an obstacle is seen).
        """
        targets = np.asarray(targets, dtype=int)
        if targets.size == 0:
            return np.zeros(0, dtype=bool)
        tx, ty = self.xs[targets], self.ys[targets]
        dx, dy = tx - origin.x, ty - origin.y
        dist = np.hypot(dx, dy)
        ok = dist <= max_range
        if heading is not None and fov < 2 * math.pi - 1e-9:
            ang = np.abs((np.arctan2(dy, dx) - heading + math.pi) % (2 * math.pi) - math.pi)
            ok &= (ang <= fov / 2) | (dist <= self.res * 1.5)
        idx = np.nonzero(ok)[0]
        if idx.size == 0:
            return np.asarray(ok, dtype=bool)
        steps = int(max_range / (self.res / 3)) + 2
        t = np.linspace(0.0, 1.0, steps)[1:-1]  # exclude both ends
        sx = origin.x + np.outer(dx[idx], t)
        sy = origin.y + np.outer(dy[idx], t)
        sx = np.clip(sx, 0, self.width - 1e-6)
        sy = np.clip(sy, 0, self.height - 1e-6)
        ks = (sy / self.res).astype(int) * self.nx + (sx / self.res).astype(int)
        own = self.cell(origin)
        blocked = opaque[ks] & (ks != targets[idx, None]) & (ks != own)
        # only samples that lie before the target along the ray count
        seen = ~blocked.any(axis=1)
        ok[idx] = seen
        return np.asarray(ok, dtype=bool)


def _runs(free: np.ndarray, dist: np.ndarray) -> np.ndarray:
    """Per cell of a 2-D boolean array: the free chord (m) along its row, 0 where not free.

    A run of free cells from ``j`` to ``k - 1`` spans its cells' centres
    (``(k - 1 - j)`` cells apart) plus, at each end, the end cell's distance
    to the wall beyond it (``dist``, in cells), so walls that do not lie on
    cell boundaries are measured exactly.
    """
    out = np.zeros(free.shape, dtype=float)
    for row, line, d in zip(out, free, dist):
        j, n = 0, len(line)
        while j < n:
            if not line[j]:
                j += 1
                continue
            k = j
            while k < n and line[k]:
                k += 1
            row[j:k] = (k - 1 - j) + d[j] + d[k - 1]
            j = k
    return out


def _shift(m: np.ndarray, di: int, dj: int) -> np.ndarray:
    out = np.zeros_like(m)
    ny, nx = m.shape
    ys = slice(max(dj, 0), ny + min(dj, 0))
    yd = slice(max(-dj, 0), ny + min(-dj, 0))
    xs = slice(max(di, 0), nx + min(di, 0))
    xd = slice(max(-di, 0), nx + min(-di, 0))
    out[ys, xs] = m[yd, xd]
    return out


@dataclass(frozen=True)
class MapGeometry:
    """What the robot knows in advance: the walls, the landmarks, its own size and sensor."""

    width: float
    height: float
    walls: tuple[tuple[float, float, float, float], ...]  # (x0, y0, x1, y1) rectangles
    landmarks: tuple[tuple[str, Pt], ...] = ()
    res: float = 0.2
    robot_radius: float = 0.25

    @cached_property
    def grid(self) -> Grid:
        return Grid(self.width, self.height, self.res)

    @cached_property
    def wall_shape(self) -> Any:
        sh = shapely()
        boxes = [sh.box(*w) for w in self.walls]
        border = sh.box(0, 0, self.width, self.height).exterior.buffer(1e-3)
        return sh.unary_union([*boxes, border])

    @cached_property
    def wall_mask(self) -> np.ndarray:
        """Cells that meet a wall."""
        g = self.grid
        m = np.zeros(g.n, dtype=bool)
        for x0, y0, x1, y1 in self.walls:
            m |= g.box_mask(Box((x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0))
        return m

    @cached_property
    def wall_distance(self) -> np.ndarray:
        """Per cell: the distance (m) from its centre to the nearest wall or the border (0 inside one)."""
        sh = shapely()
        g = self.grid
        pts = sh.points(np.stack([g.xs, g.ys], axis=1))
        return np.asarray(sh.distance(self.wall_shape, pts), dtype=float)

    @cached_property
    def robot_blocked(self) -> np.ndarray:
        """Cells whose centre is closer than the robot's radius (plus a margin) to a wall or the border."""
        return np.asarray(self.wall_distance < self.robot_radius + CLEARANCE)

    @cached_property
    def passage_width(self) -> np.ndarray:
        """Per cell: the width of free space through it, its shorter free chord (horizontal or vertical).

        The chord is the run of wall-free cells through the cell along a
        row or a column.  In a corridor or a doorway it is the passage's
        width; in a room, even next to a wall, the room's extent.  (Only the
        two axes are measured: a passage at 45 degrees reads up to 1.4 times
        wider than it is.)
        """
        g = self.grid
        free = ~self.wall_mask.reshape(g.ny, g.nx)
        d = self.wall_distance.reshape(g.ny, g.nx) / self.res
        return np.asarray(np.minimum(_runs(free, d), _runs(free.T, d.T).T).reshape(-1) * self.res, dtype=float)

    def segment_free(self, a: Pt, b: Pt, blocked: np.ndarray | None = None) -> bool:
        """Can the robot's centre move straight from a to b, keeping its radius (and margin) off the walls?"""
        if blocked is not None and bool(blocked[self.grid.line_cells(a, b)].any()):
            return False
        sh = shapely()
        line = sh.Point(a.x, a.y) if a == b else sh.LineString([(a.x, a.y), (b.x, b.y)])
        return bool(line.distance(self.wall_shape) >= self.robot_radius + CLEARANCE - 1e-9)

    def landmark(self, name: str) -> Pt:
        for n, p in self.landmarks:
            if n == name:
                return p
        raise KeyError(name)


def polyline_length(pts: Sequence[Pt]) -> float:
    return sum(pts[i].dist(pts[i + 1]) for i in range(len(pts) - 1))


def heading_to(a: Pt, b: Pt) -> float:
    return math.atan2(b.y - a.y, b.x - a.x)


def along(path: tuple[Pt, ...] | list[Pt], dist: float) -> Pt:
    """The point ``dist`` metres along a polyline (its end if the polyline is shorter)."""
    if not path:
        raise ValueError("empty path")
    left = dist
    for i in range(len(path) - 1):
        a, b = path[i], path[i + 1]
        L = a.dist(b)
        if left <= L + 1e-9:
            t = 0.0 if L == 0 else left / L
            return Pt.of(a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t)
        left -= L
    return path[-1]


def point_back(pts: Sequence[Pt], dist: float) -> Pt:
    """The vertex before the end, or the point ``dist`` back along the last piece if that is longer."""
    if len(pts) < 2:
        return pts[0]
    a, b = pts[-2], pts[-1]
    L = a.dist(b)
    if L <= dist + 1e-9:
        return a
    t = dist / L
    return Pt.of(b.x + (a.x - b.x) * t, b.y + (a.y - b.y) * t)


def cells_to_points(grid: Grid, cells: Iterable[int]) -> list[Pt]:
    return [grid.center(k) for k in cells]


@dataclass(frozen=True, order=True)
class Manip:
    """One way to move an object out of the way (seed 000 Fig. 8).

    The robot drives from ``home`` to ``pick_conf`` (the pick path), grasps
    the object it expects at ``obj_at``, drags it along the carry path to
    ``release`` (the object then rests at ``place``), and drives back home
    along the return path, which the generator checked with the object
    already placed.
    """

    obj: str
    home: Pt
    pick_conf: Pt
    obj_at: Pt
    place: Pt
    release: Pt
    pick_path: tuple[Pt, ...]
    carry_path: tuple[Pt, ...]
    return_path: tuple[Pt, ...]
    survey: Region | None = None  # what must be observed (from the pick configuration) before placing

    @property
    def offset(self) -> tuple[float, float]:
        return (self.place.x - self.release.x, self.place.y - self.release.y)

    @property
    def lengths(self) -> tuple[float, float, float]:
        return (
            polyline_length(self.pick_path),
            polyline_length(self.carry_path),
            polyline_length(self.return_path),
        )

    def __str__(self) -> str:
        return f"{self.obj}:{self.obj_at}->{self.place}"


def snap_free(geom: MapGeometry, p: Pt, tol: float) -> Pt:
    """The centre of ``p``'s grid cell or, when the robot cannot stand there (too close to a wall: a move
    stopped in a doorway), the nearest neighbouring centre where it can, within ``tol`` of ``p``."""
    g = geom.grid
    own = g.cell(p)
    i, j = g.ij(own)
    near = [(g.center(jj * g.nx + ii).dist(p), jj * g.nx + ii) for ii in (i - 1, i, i + 1) for jj in (j - 1, j, j + 1)
            if 0 <= ii < g.nx and 0 <= jj < g.ny]
    free = sorted((d, k) for d, k in near if not geom.robot_blocked[k] and d <= tol)
    return g.center(own if not geom.robot_blocked[own] or not free else free[0][1])
