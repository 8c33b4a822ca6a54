"""Grid motion planning in the belief: Dijkstra trees, string-pulled paths, soft costs.

The robot is a disc; walls (grown by its radius) are impassable.  Known
movable objects are passable at a cost (``clear_cost``, paid once on
entering the object's grown footprint: moving it out of the way); fog
costs its expected clearance cost per metre (below).  Around each object lies its *epsilon-shadow* (the footprint
grown by ``k·σ``, where ``BClear`` fails): without foresight entering it
costs a look (``look_cost``: one more look will probably show the way is
clear); with foresight it costs the expected price of finding the object
in the way once it is seen better, a penalty that grows with the shadow's
width (seed 000, footnote 2), so paths keep away from uncertain objects.

Penalties are paid per region *entered*, so each cell carries a bit mask
of the regions covering it and an edge pays for the bits it gains.

Fog is not free: every metre run through it costs its expected clearance
cost under the belief (:mod:`.fogcost`: the posterior density of objects
times the width a path sweeps times ``clear_cost``), on top of its length,
in the Dijkstra trees and in the exact costs of straight moves alike, so a
route past a known obstacle and a route through unseen space are compared
in the same currency.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from nowplan.domains.namo.belief import NamoBelief, k_of
from nowplan.domains.namo.fogcost import fog_along, fog_price
from nowplan.domains.namo.geometry import Box, Grid, Pt, Region

SQRT2 = math.sqrt(2.0)
INF = float("inf")


def dijkstra(
    grid: Grid,
    passable: Sequence[bool] | np.ndarray,
    source: int,
    masks: Sequence[int] | None = None,
    penalties: Sequence[float] | None = None,
    target: int | None = None,
    per_metre: Sequence[float] | np.ndarray | None = None,
) -> tuple[list[float], list[int]]:
    """Single-source shortest paths over 8-connected free cells (no corner cutting).

    An edge costs its length, times ``1 + per_metre[u]/2 + per_metre[v]/2``
    when per-metre cell costs are given (half of the edge lies in each
    cell), plus the penalties of the regions it enters.
    """
    nx, ny, res = grid.nx, grid.ny, grid.res
    free = passable.tolist() if isinstance(passable, np.ndarray) else list(passable)
    extra = None
    if per_metre is not None:
        extra = (per_metre / 2.0).tolist() if isinstance(per_metre, np.ndarray) else [x / 2.0 for x in per_metre]
    n = nx * ny
    dist = [INF] * n
    parent = [-1] * n
    if not free[source]:
        return dist, parent
    dist[source] = 0.0
    heap = [(0.0, source)]
    diag = res * SQRT2
    pen_cache: dict[int, float] = {0: 0.0}

    def penalty(bits: int) -> float:
        p = pen_cache.get(bits)
        if p is None:
            p, b, i = 0.0, bits, 0
            while b:
                if b & 1 and penalties is not None:
                    p += penalties[i]
                b >>= 1
                i += 1
            pen_cache[bits] = p
        return p

    while heap:
        d, u = heapq.heappop(heap)
        if d > dist[u]:
            continue
        if u == target:
            break
        ui, uj = u % nx, u // nx
        mu = masks[u] if masks is not None else 0
        for di, dj in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (1, -1), (-1, 1), (-1, -1)):
            vi, vj = ui + di, uj + dj
            if vi < 0 or vj < 0 or vi >= nx or vj >= ny:
                continue
            v = vj * nx + vi
            if not free[v]:
                continue
            if di and dj:
                if not free[uj * nx + vi] or not free[vj * nx + ui]:
                    continue
                step = diag
            else:
                step = res
            nd = d + (step if extra is None else step * (1.0 + extra[u] + extra[v]))
            if masks is not None:
                mv = masks[v]
                gain = mv & ~mu
                if gain:
                    nd += penalty(gain)
            if nd < dist[v]:
                dist[v] = nd
                parent[v] = u
                heapq.heappush(heap, (nd, v))
    return dist, parent


def trace_back(parent: Sequence[int], source: int, target: int) -> list[int] | None:
    if source == target:
        return [source]
    if parent[target] < 0:
        return None
    out = [target]
    k = target
    while k != source:
        k = parent[k]
        if k < 0:
            return None
        out.append(k)
    out.reverse()
    return out


def _far(box: Box, a: Pt, b: Pt, margin: float) -> bool:
    """Is the box surely further than ``margin`` from segment ab (their bounding boxes apart)?"""
    x0, y0, x1, y1 = box.bounds
    return (
        min(a.x, b.x) - margin > x1 or max(a.x, b.x) + margin < x0
        or min(a.y, b.y) - margin > y1 or max(a.y, b.y) + margin < y0
    )


@dataclass
class CostMap:
    grid: Grid
    passable: np.ndarray
    masks: list[int]
    penalties: list[float]
    labels: list[str]  # what each bit stands for, e.g. "box1" or "box1~shadow"
    radius: float = 0.25
    objects: list[tuple[Box, float, int, int]] = field(default_factory=list)
    fog_cost: float = 0.0  # expected clearance cost per metre of fog where objects block (fogcost.fog_price)
    per_metre: np.ndarray | None = None  # per cell: fog's expected clearance cost per metre, 0 where observed (None: all 0)


def build_costmap(belief: NamoBelief, foresight: bool, stuck_impassable: bool = True) -> CostMap:
    geom, p = belief.geom, belief.params
    g = geom.grid
    passable = ~geom.robot_blocked
    if belief.bumps:
        passable = passable.copy()
        passable[list(belief.bumps)] = False
    masks = [0] * g.n
    penalties: list[float] = []
    labels: list[str] = []
    r = geom.robot_radius
    k = k_of(p.eps_clear)
    objects: list[tuple[Box, float, int, int]] = []  # box, shadow width, core bit, shadow bit
    for o in belief.free_objects():
        core = g.box_mask(o.box, r)
        width = k * o.sigma
        stuck = belief.stuck(o.name)
        if stuck and stuck_impassable:  # nowhere to put it: impassable (with its shadow) for now
            passable = passable & ~g.box_mask(o.box, r + width)
            continue
        bit = 1 << len(penalties)
        penalties.append(p.clear_cost * (4.0 if stuck else 1.0))
        labels.append(o.name)
        objects.append((o.box, width, bit, 0))
        for c in np.nonzero(core)[0].tolist():
            masks[c] |= bit
        ring = g.box_mask(o.box, r + width) & ~core
        if ring.any():
            objects[-1] = (o.box, width, bit, 1 << len(penalties))
            bit = 1 << len(penalties)
            # without foresight a shadow costs a look; with it, the expected cost of finding the
            # object in the way once it is seen better (seed 000 footnote 2)
            penalties.append(p.shadow_cost * min(1.0, width / r) if foresight else p.look_cost)
            labels.append(o.name + "~shadow")
            for c in np.nonzero(ring)[0].tolist():
                masks[c] |= bit
    price = fog_price(belief)
    fog_cost = price.per_metre
    per_metre = np.where(belief.observed, 0.0, price.cells) if fog_cost > 0 else None
    return CostMap(g, passable, masks, penalties, labels, r, objects, fog_cost, per_metre)


class PathPlanner:
    """Paths for one belief version (cached on the belief) with or without shadows."""

    def __init__(self, belief: NamoBelief, foresight: bool, stuck_impassable: bool = True) -> None:
        self.belief = belief
        self.foresight = foresight
        self.cm = build_costmap(belief, foresight, stuck_impassable)
        self._trees: dict[int, tuple[list[float], list[int]]] = {}
        # answers for this belief version (paths and straight-line checks repeat across the
        # planner's generator calls and the triggers)
        self._paths: dict[tuple[Pt, Pt], list[Pt] | None] = {}
        self._lines: dict[tuple[Pt, Pt, int], bool] = {}
        self._fallback: PathPlanner | None = None
        self._stuck_impassable = stuck_impassable

    def fallback(self) -> PathPlanner | None:
        """The same planner with unmovable-looking objects expensive instead of impassable."""
        if not self._stuck_impassable:
            return None
        if self._fallback is None:
            self._fallback = PathPlanner(self.belief, self.foresight, stuck_impassable=False)
        return self._fallback

    @staticmethod
    def of(belief: NamoBelief, foresight: bool) -> PathPlanner:
        c = belief.cache()
        stuck = frozenset(n for n in belief.unmovable if belief.stuck(n))
        key = ("planner", foresight, stuck)
        pp = c.get(key)
        if pp is None:
            pp = PathPlanner(belief, foresight)
            c[key] = pp
        assert isinstance(pp, PathPlanner)
        return pp

    def _source(self, p: Pt) -> int:
        g = self.cm.grid
        k = g.cell(p)
        if self.cm.passable[k] or not self.belief.geom.robot_blocked[k]:
            return k  # (a cell blocked only by an object's zone: the robot is there, it can leave)
        # the nearest cell off the walls (the robot's pose estimate may sit on a grown wall)
        d = np.hypot(g.xs - p.x, g.ys - p.y)
        d[~self.cm.passable] = np.inf
        return int(np.argmin(d))

    def tree(self, source: Pt) -> tuple[list[float], list[int]]:
        s = self._source(source)
        t = self._trees.get(s)
        if t is None:
            passable = self.cm.passable
            if not passable[s]:  # let the robot leave an object's zone it stands in (moving away only)
                g = self.cm.grid
                c = g.center(s)
                escape = g.disk_mask(c, 0.45) & ~self.belief.geom.robot_blocked
                for o in self.belief.free_objects():
                    here = o.box.distance_to_segment(c, c)
                    if here < self.cm.radius + 3 * o.sigma + 0.3:
                        x0, y0, x1, y1 = o.box.bounds
                        dx = np.maximum(np.maximum(x0 - g.xs, 0.0), g.xs - x1)
                        dy = np.maximum(np.maximum(y0 - g.ys, 0.0), g.ys - y1)
                        escape &= np.hypot(dx, dy) > here + 0.05
                escape[s] = True
                passable = passable | escape
            t = dijkstra(self.cm.grid, passable, s, self.cm.masks, self.cm.penalties, per_metre=self.cm.per_metre)
            self._trees[s] = t
        return t

    def cost(self, source: Pt, target: Pt) -> float:
        dist, _ = self.tree(source)
        return dist[self.cm.grid.cell(target)]

    def path(self, source: Pt, target: Pt) -> list[Pt] | None:
        """A string-pulled polyline from ``source`` to ``target`` (both included), or None."""
        key = (source, target)
        if key not in self._paths:
            self._paths[key] = self._path(source, target)
        out = self._paths[key]
        return None if out is None else list(out)

    def _path(self, source: Pt, target: Pt) -> list[Pt] | None:
        g = self.cm.grid
        s = self._source(source)
        t = g.cell(target)
        _, parent = self.tree(source)
        cells = trace_back(parent, s, t)
        if cells is None:
            fb = self.fallback()
            return fb.path(source, target) if fb is not None else None
        pts = self.smooth(cells)
        pts[0] = source
        if pts[-1] != target:
            if len(pts) > 1 and g.cell(pts[-1]) == t:
                pts[-1] = target
            else:
                pts.append(target)
        return pts

    def smooth(self, cells: list[int]) -> list[Pt]:
        g = self.cm.grid
        pts = [g.center(k) for k in cells]
        if len(cells) <= 2:
            return pts
        masks = self.cm.masks
        out = [pts[0]]
        i = 0
        while i < len(cells) - 1:
            j = i + 1
            allowed = masks[cells[i]] | masks[cells[j]]
            while j + 1 < len(cells):
                allowed_next = allowed | masks[cells[j + 1]]
                if not self.line_ok(pts[i], pts[j + 1], allowed_next):
                    break
                allowed = allowed_next
                j += 1
            out.append(pts[j])
            i = j
        return out

    def line_ok(self, a: Pt, b: Pt, allowed: int) -> bool:
        key = (a, b, allowed)
        hit = self._lines.get(key)
        if hit is None:
            hit = self._lines[key] = self._line_ok(a, b, allowed)
        return hit

    def _line_ok(self, a: Pt, b: Pt, allowed: int) -> bool:
        ks = self.cm.grid.line_cells(a, b)
        if not self.cm.passable[ks].all():
            return False
        m = 0
        for k in ks.tolist():
            m |= self.cm.masks[k]
        if (m & ~allowed) != 0 or not self.belief.geom.segment_free(a, b):
            return False
        r = self.cm.radius
        for box, width, core, shadow in self.cm.objects:  # exactly, not just by cells
            if _far(box, a, b, r + width):
                continue
            d = box.distance_to_segment(a, b)
            if d < r and not (allowed & core):
                return False
            if d < r + width and shadow and not (allowed & (shadow | core)):
                return False
        return True

    def segment_cost(self, a: Pt, b: Pt) -> float:
        """Length plus the penalties of the regions a straight move from a to b enters.

        Which object (or ε-shadow) the move enters is decided exactly, from
        the distance between the segment and the object's box, not from the
        grid cells the segment crosses: a cell-sized over-approximation would
        charge a move that passes an object 0.3 m away for clearing it (and
        make the shorter-path trigger re-route around objects just placed
        beside the path).  The part of the move that runs through fog (the
        fraction of the cells it crosses that are fog) costs the fog's
        expected clearance cost per metre as well.
        """
        ks = self.cm.grid.line_cells(a, b)
        if not self.cm.passable[ks].all():
            return INF
        fog = fog_along(self.cm.per_metre, ks) * a.dist(b) if self.cm.per_metre is not None else 0.0
        r = self.cm.radius
        swept = Region(a, b, r)  # the volume BClear tests: swept after leaving a
        pen = 0.0
        for box, width, core, shadow in self.cm.objects:
            if _far(box, a, b, r + width) or not swept.hits_box(box, width):
                continue
            inside = box.distance_to_segment(a, a) < r  # a move starting inside pays nothing for it
            if not inside and swept.hits_box(box, 0.0):
                pen += self.cm.penalties[core.bit_length() - 1]
            if shadow and not inside and box.distance_to_segment(a, a) >= r + width:
                pen += self.cm.penalties[shadow.bit_length() - 1]
        return a.dist(b) + fog + pen

    def polyline_cost(self, pts: Sequence[Pt]) -> float:
        return sum(self.segment_cost(pts[i], pts[i + 1]) for i in range(len(pts) - 1))
