"""Where to put an obstacle: the placement generator with foresight and connectivity.

To clear region ``R`` the generator picks an object in the way and a
:class:`~nowplan.domains.namo.geometry.Manip`: a pick configuration next to
it and a placement, such that (seed 000 Fig. 8)

1. a pick path exists from the robot's pose to the pick configuration, hand empty;
2. a carry path exists from there to the release configuration, dragging the object;
3. a return path exists from the release configuration back home, hand empty,
   *with the object placed* — the robot stays connected to where it started.

All three run through observed free space only.  The placement must not
meet ``R`` nor any other region the goal being planned needs clear (local
foresight, which regression alone already guarantees).  With foresight on,
regions that *any* plan on the stack needs clear (the taboo regions, seed
000 III-B) are avoided when possible: they cost ``taboo_cost`` instead of
being forbidden.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator, Mapping
from typing import Any

import numpy as np

from nowplan.core.atoms import Goal, Var
from nowplan.domains.namo.belief import NamoBelief, k_of
from nowplan.domains.namo.generators import foresight, robot_at_in
from nowplan.domains.namo.geometry import Box, Grid, Manip, MapGeometry, Pt, Region, shapely
from nowplan.domains.namo.paths import INF, dijkstra, trace_back

O, R, EX, EXO, M = Var("o"), Var("r"), Var("ex"), Var("exo"), Var("m")
HOME, PC, PLACE, SPOT, ONLY = Var("home"), Var("pc"), Var("place"), Var("spot"), Var("only")

PLACE_MARGIN = 0.08  # the placed object keeps this far from regions that must stay clear


def gen_manip_fields(bindings: Mapping[Var, Any], goal: Goal, belief: NamoBelief, context: Any) -> Iterator[dict[Var, Any]]:
    m = bindings.get(M)
    if isinstance(m, Manip):
        yield {HOME: m.home, PC: m.pick_conf}


def taboo_regions(context: Any) -> list[Region]:
    """Every region some plan on the stack needs clear: its BClear requirements and its moves' volumes."""
    if not foresight(context):
        return []
    out: dict[Region, None] = {}
    for a in context.requirements("BClear"):
        if isinstance(a.args[0], Region):
            out[a.args[0]] = None
    for plan in context.plan_stack:
        for step in plan.steps:
            act = step.action
            if act is None:
                continue
            for pre in act.preconditions(None):
                if pre.predicate == "BClear" and isinstance(pre.args[0], Region):
                    out[pre.args[0]] = None
    return list(out)


def hard_regions(goal: Goal, obj: str, cleared: Region) -> list[Region]:
    out = [cleared]
    for a in goal.atoms:
        if a.predicate == "BClear" and isinstance(a.args[0], Region) and obj not in a.args[1]:
            if a.args[0] != cleared:
                out.append(a.args[0])
    return out


def gen_place(bindings: Mapping[Var, Any], goal: Goal, belief: NamoBelief, context: Any) -> Iterator[dict[Var, Any]]:
    """An object in region ``?r`` (not excepted) and how to move it out of the way."""
    region, ex = bindings.get(R), bindings.get(EX)
    home = robot_at_in(goal) or belief.nominal()
    if belief.held is not None:  # finish the placement under way (or just put the object down)
        m = belief.held_manip
        if m is None:
            return
        if not isinstance(region, Region) or not isinstance(ex, frozenset):
            region, ex = Region(m.place, m.place, 0.0), frozenset()
        if belief.held not in ex and m.home == home:
            size = belief.objects[belief.held].size if belief.held in belief.objects else (0.0, 0.0)
            yield {R: region, EX: ex, O: belief.held, EXO: ex | {belief.held}, M: m, HOME: home,
                   PC: m.pick_conf, **_spot(m, belief.held, size)}
        return
    if not isinstance(region, Region) or not isinstance(ex, frozenset):
        return
    blockers = belief.blockers(region, belief.params.eps_clear, ex)
    blockers.sort(key=lambda n: belief.objects[n].center.dist(home))
    taboo = taboo_regions(context)
    for name in blockers[:3]:
        hard = hard_regions(goal, name, region)
        size = belief.objects[name].size
        # regression order: the other objects in the region and not excepted are moved before this one
        gone = frozenset(blockers) - {name}
        for m in manip_options(belief, name, home, tuple(hard), tuple(taboo), n=2, gone=gone):
            yield {O: name, EXO: ex | {name}, M: m, HOME: home, PC: m.pick_conf, **_spot(m, name, size)}


def _spot(m: Manip, name: str, size: tuple[float, float]) -> dict[Var, Any]:
    """The placed box and the disc around it that must be free of other objects when it is put down."""
    box = Box(m.place.x, m.place.y, *size)
    return {PLACE: box, SPOT: Region(m.place, m.place, math.hypot(*size) / 2), ONLY: frozenset({name})}


# -- geometry of manipulation -------------------------------------------------------------
def _dilate_box(grid: Grid, mask: np.ndarray, hw: float, hh: float) -> np.ndarray:
    """Cells from which a box of half-size (hw, hh) centred there meets ``mask``."""
    m = mask.reshape(grid.ny, grid.nx)
    rx = int(math.ceil(hw / grid.res - 0.5 + 1e-9))
    ry = int(math.ceil(hh / grid.res - 0.5 + 1e-9))
    out = m.copy()
    for d in range(1, rx + 1):
        out[:, d:] |= m[:, :-d]
        out[:, :-d] |= m[:, d:]
    m2 = out.copy()
    for d in range(1, ry + 1):
        out[d:, :] |= m2[:-d, :]
        out[:-d, :] |= m2[d:, :]
    return out.reshape(-1)


def _carry_check(geom: MapGeometry, box: Box, offset: tuple[float, float]) -> Callable[[Pt, Pt], bool]:
    """Exact test of a straight drag: the robot and the swept object box stay off the walls."""
    sh = shapely()
    hw, hh = box.w / 2, box.h / 2

    def ok(a: Pt, b: Pt) -> bool:
        if not geom.segment_free(a, b):
            return False
        corners = [(p.x + offset[0] + sx * hw, p.y + offset[1] + sy * hh)
                   for p in (a, b) for sx in (-1, 1) for sy in (-1, 1)]
        return bool(sh.MultiPoint(corners).convex_hull.distance(geom.wall_shape) >= 0.03)

    return ok


def _box_dist(g: Grid, box: Box) -> np.ndarray:
    """Distance from each cell centre to the box."""
    x0, y0, x1, y1 = box.bounds
    dx = np.maximum(np.maximum(x0 - g.xs, 0.0), g.xs - x1)
    dy = np.maximum(np.maximum(y0 - g.ys, 0.0), g.ys - y1)
    return np.hypot(dx, dy)


def _box_off_walls(
    geom: MapGeometry, w: float, h: float, dx: float = 0.0, dy: float = 0.0, tol: float = 0.02
) -> np.ndarray:
    """Cells ``c`` where a w x h box centred at ``centre(c) + (dx, dy)`` stays off every wall and in the map."""
    g = geom.grid
    xs, ys = g.xs + dx, g.ys + dy
    hw, hh = w / 2 - tol, h / 2 - tol
    ok = (xs - hw >= 0) & (ys - hh >= 0) & (xs + hw <= geom.width) & (ys + hh <= geom.height)
    for x0, y0, x1, y1 in geom.walls:
        ok &= ~((xs - hw < x1) & (xs + hw > x0) & (ys - hh < y1) & (ys + hh > y0))
    return ok


def _shift_cells(grid: Grid, mask: np.ndarray, di: int, dj: int, fill: bool) -> np.ndarray:
    """``out[c] = mask[c + (di, dj)]`` (``fill`` outside the grid)."""
    m = mask.reshape(grid.ny, grid.nx)
    out = np.full_like(m, fill)
    ny, nx = m.shape
    src_y = slice(max(dj, 0), ny + min(dj, 0))
    dst_y = slice(max(-dj, 0), ny + min(-dj, 0))
    src_x = slice(max(di, 0), nx + min(di, 0))
    dst_x = slice(max(-di, 0), nx + min(-di, 0))
    out[dst_y, dst_x] = m[src_y, src_x]
    return out.reshape(-1)


def smooth_cells(
    grid: Grid, free: np.ndarray, cells: list[int], exact: Callable[[Pt, Pt], bool] | None = None
) -> list[Pt]:
    """String-pull a cell path: shortcuts must stay on free cells (and pass ``exact`` if given)."""
    pts = [grid.center(k) for k in cells]
    if len(pts) <= 2:
        return pts
    out = [pts[0]]
    i = 0
    while i < len(pts) - 1:
        j = i + 1
        while j + 1 < len(pts) and bool(free[grid.line_cells(pts[i], pts[j + 1])].all()) and (
            exact is None or exact(pts[i], pts[j + 1])
        ):
            j += 1
        out.append(pts[j])
        i = j
    return out


def manip_options(
    belief: NamoBelief, name: str, home: Pt, hard: tuple[Region, ...], taboo: tuple[Region, ...], n: int = 2,
    gone: frozenset[str] = frozenset(),
) -> list[Manip]:
    """Up to ``n`` ways to move ``name`` from ``home``; objects in ``gone`` will have been moved already."""
    key = ("manip", name, home, hard, taboo, n, gone)
    cache = belief.cache()
    if key in cache:
        return cache[key]  # type: ignore[no-any-return]
    out = _manip_options(belief, name, home, hard, taboo, n, gone)
    cache[key] = out
    if not out and not gone:  # nowhere to put it from here: route around it until something new is seen
        belief.unmovable[name] = belief.percept
    return out


def _manip_options(
    belief: NamoBelief, name: str, home: Pt, hard: tuple[Region, ...], taboo: tuple[Region, ...], n: int,
    gone: frozenset[str] = frozenset(),
) -> list[Manip]:
    geom, params = belief.geom, belief.params
    g = geom.grid
    r = geom.robot_radius
    est = belief.objects[name]
    obox = est.box
    k = k_of(params.eps_clear)
    others = np.zeros(g.n, dtype=bool)
    for o in belief.free_objects({name} | gone):
        others |= g.box_mask(o.box, k * o.sigma)
    base = ~geom.robot_blocked & belief.observed & ~g.dilate(others, r)
    # the pick happens once the object is localised (BVRelPose), so keep the clearance that needs
    clearance = k * min(est.sigma, params.eps_pick)
    own = g.box_mask(obox, r + clearance)
    hc = g.cell(home)
    free_pick = base & ~own
    free_pick[hc] = True
    dist_pick, par_pick = dijkstra(g, free_pick, hc)
    # grasp from right next to the object: the nearest free cells around it (at most a cell further)
    gap = _box_dist(g, obox)
    ring_cells = [c for c in np.nonzero(free_pick)[0].tolist() if dist_pick[c] < INF and c != hc]
    if not ring_cells:
        return []
    nearest = min(gap[c] for c in ring_cells)
    pcs = sorted((dist_pick[c], c) for c in ring_cells if gap[c] <= max(nearest, r + clearance) + g.res * 0.75)
    if not pcs:
        return []
    base_home = base.copy()
    base_home[hc] = True
    dist_home, _ = dijkstra(g, base_home, hc)
    # where the object's centre may go: its footprint off the walls (exactly), off other objects and
    # on observed floor (its own cells count as floor: they are hidden behind its front face)
    # (fog is allowed at a price: the robot itself stays on observed floor, and dragging into
    # something unseen just stops the drag)
    hidden_own = g.box_mask(obox, k * est.sigma + g.res)
    obj_ok = ~_dilate_box(g, others, obox.w / 2, obox.h / 2)
    obj_known = ~_dilate_box(g, ~belief.observed & ~hidden_own, obox.w / 2, obox.h / 2)
    results: list[tuple[float, Manip]] = []
    for _, pc in pcs[:2]:
        pcp = g.center(pc)
        di = int(round((obox.cx - pcp.x) / g.res))
        dj = int(round((obox.cy - pcp.y) / g.res))
        offset = (obox.cx - pcp.x, obox.cy - pcp.y)
        carry_free = base & _shift_cells(g, obj_ok, di, dj, False) & _box_off_walls(geom, obox.w, obox.h, *offset)
        carry_free[pc] = True
        dist_c, par_c = dijkstra(g, carry_free, pc)
        cands: list[tuple[float, int, Box]] = []
        for c in np.nonzero(np.isfinite(np.asarray(dist_c)))[0].tolist():
            if c == pc:
                continue
            rel = g.center(c)
            box = Box(round(rel.x + offset[0], 2), round(rel.y + offset[1], 2), obox.w, obox.h)
            if any(h.hits_box(box, PLACE_MARGIN) for h in hard):
                continue
            if box.distance_to_segment(home, home) <= r + 0.05:
                continue
            score = dist_c[c] + dist_home[c]
            if score == INF:
                continue
            oc = c + dj * g.nx + di
            if not (0 <= oc < g.n and obj_known[oc]):
                score += params.fog_place_cost
            if any(t.hits_box(box, PLACE_MARGIN) for t in taboo):
                score += params.taboo_cost
            cands.append((score, c, box))
        cands.sort(key=lambda x: (x[0], x[1]))
        found = 0
        for score, c, box in cands[:40]:
            placed = g.box_mask(box, r)
            free_ret = base & ~placed
            free_ret[hc] = True
            if params.connectivity:
                dist_r, par_r = dijkstra(g, free_ret, hc, target=c)
                if dist_r[c] == INF:
                    continue
            else:  # the check of Fig. 8 switched off: the placed object is ignored
                dist_r, par_r = dijkstra(g, base_home, hc, target=c)
                if dist_r[c] == INF:
                    continue
            pick_cells = trace_back(par_pick, hc, pc)
            carry_cells = trace_back(par_c, pc, c)
            ret_cells = trace_back(par_r, hc, c)
            if pick_cells is None or carry_cells is None or ret_cells is None:
                continue
            ret_cells.reverse()
            pick_path = smooth_cells(g, free_pick, pick_cells, geom.segment_free)
            pick_path[0] = home
            ret_path = smooth_cells(g, free_ret if params.connectivity else base_home, ret_cells, geom.segment_free)
            ret_path[-1] = home
            m = Manip(
                obj=name, home=home, pick_conf=g.center(pc), obj_at=est.center,
                place=box.center, release=g.center(c),
                pick_path=tuple(pick_path),
                carry_path=tuple(smooth_cells(g, carry_free, carry_cells, _carry_check(geom, obox, offset))),
                return_path=tuple(ret_path),
            )
            results.append((score, m))
            found += 1
            if found >= n:
                break
    results.sort(key=lambda x: x[0])
    return [m for _, m in results[:n]]
