"""Where to put an obstacle: the placement generator with foresight and connectivity.

To clear region ``R`` the generator picks an object in the way and a
:class:`~nowplan.domains.namo.geometry.Manip`: a pick configuration next to
it and a placement, such that (seed 000 Fig. 8)

1. a pick path exists from the robot's pose to the pick configuration, hand empty;
2. a carry path exists from there to the release configuration, dragging the object;
3. a return path exists from the release configuration back home, hand empty,
   *with the object placed* — the robot stays connected to where it started.

All three run through observed free space; only when that is impossible
are they planned through fog, and then the carry volume (``Manip.survey``)
must be observed, from the pick configuration, before the object is put
down (``Observed(survey)`` is a precondition of ``Place``).  The placement must not
meet ``R`` nor any other region the goal being planned needs clear (local
foresight, which regression alone already guarantees).  With foresight on,
regions that *any* plan on the stack needs clear (the taboo regions, seed
000 III-B) are avoided when possible: they cost ``taboo_cost`` instead of
being forbidden.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from collections.abc import Callable, Iterator, Mapping
from typing import Any

import numpy as np

from nowplan.core.atoms import Goal, Var
from nowplan.domains.namo.belief import NamoBelief, k_of
from nowplan.domains.namo.generators import foresight, robot_at_in
from nowplan.domains.namo.geometry import GRAZE_OK, Box, Grid, Manip, MapGeometry, Pt, Region, shapely
from nowplan.domains.namo.paths import INF, dijkstra, trace_back
from nowplan.domains.namo.regions import hard_regions, kept_regions, taboo_regions

try:  # optional: a faster connectivity test (imported here, not inside a timed planning call)
    from scipy import ndimage
except ImportError:  # pragma: no cover
    ndimage = None

O, R, EX, EXO, M = Var("o"), Var("r"), Var("ex"), Var("exo"), Var("m")
HOME, PC, PLACE, SPOT, ONLY = Var("home"), Var("pc"), Var("place"), Var("spot"), Var("only")
SURVEY, HIDDEN, KEEP = Var("survey"), Var("hidden"), Var("keep")
NOTHING = Region(Pt(-1.0, -1.0), Pt(-1.0, -1.0), 0.0)  # what a pick un-observes when it hides no fog

PLACE_MARGIN = 0.08  # the placed object keeps this far from regions that must stay clear


def gen_manip_fields(bindings: Mapping[Var, Any], goal: Goal, belief: NamoBelief, context: Any) -> Iterator[dict[Var, Any]]:
    """A pick's home and configuration, and what it un-observes: a carry volume partly hidden by the object."""
    m = bindings.get(M)
    if isinstance(m, Manip):
        hid = m.survey if m.survey is not None and belief.fog_behind(m.survey, m.obj) else NOTHING
        yield {HOME: m.home, PC: m.pick_conf, HIDDEN: hid}


def gen_place(bindings: Mapping[Var, Any], goal: Goal, belief: NamoBelief, context: Any) -> Iterator[dict[Var, Any]]:
    """An object in region ``?r`` (not excepted) and how to move it out of the way."""
    region, ex = bindings.get(R), bindings.get(EX)
    # while an object is held, the plan's moves (and any other manipulation) start once it is put
    # down, from the held manipulation's home (as gen_move plans them)
    held_home = belief.held_manip.home if belief.held is not None and belief.held_manip is not None else None
    home = robot_at_in(goal) or held_home or belief.nominal()
    if belief.held is not None:
        yield from _place_held(region, ex, home, goal, belief, context)
        # ... or, once it is down, move another object out of the region: a plan made while holding
        # one object may need to clear others first (a missed detection shows one only now)
    if not isinstance(region, Region) or not isinstance(ex, frozenset):
        return
    blockers = belief.blockers(region, belief.params.eps_clear, ex)
    blockers.sort(key=lambda n: belief.objects[n].center.dist(home))
    taboo = taboo_regions(context)
    for name in blockers[:3]:
        hard_list = hard_regions(goal, name, region)
        size = belief.objects[name].size
        # regression order: the other objects in the region and not excepted are moved before this one
        gone = frozenset(blockers) - {name}
        options = manip_options(belief, name, home, tuple(hard_list), tuple(taboo), n=2, gone=gone)
        if not options and not gone:
            manip_options(belief, name, home, (region,), (), n=1)  # is it movable at all? (marks it if not)
        for m in options:
            yield {O: name, EXO: ex | {name}, M: m, HOME: home, PC: m.pick_conf, **_spot(m, name, size, belief.geom.robot_radius)}


def _place_held(region: Any, ex: Any, home: Pt, goal: Goal, belief: NamoBelief, context: Any) -> Iterator[dict[Var, Any]]:
    """Finish the placement under way of the object held, place it elsewhere, or just put it down."""
    m, held = belief.held_manip, belief.held
    if m is None or held is None or held not in belief.objects:
        return
    only_hand = not isinstance(region, Region) or not isinstance(ex, frozenset)
    if only_hand:  # only the hand must be emptied: "cleared" is the spot the object goes to
        region, ex = Region(m.place, m.place, 0.0), frozenset()
    assert isinstance(region, Region) and isinstance(ex, frozenset)
    if held in ex or m.home != home:
        return
    size = belief.objects[held].size
    options = [m]
    spot = _spot(m, held, size, belief.geom.robot_radius)
    pc = belief.nominal()
    grip = belief.grip[0] if belief.grip is not None else np.array(m.offset)
    at = Pt.of(belief.robot_mean[0] + grip[0], belief.robot_mean[1] + grip[1])
    unseeable = (m.survey is not None and not belief.is_observed(m.survey)
                 and belief.futile_looks.get((m.pick_conf, f"look:{m.survey}")) == belief.percept)
    away = not belief.at(m.pick_conf)  # the grasp pushed the robot off its pick configuration
    # where the goal being planned needs the object not to be: the region cleared, regions it needs
    # clear of the object, later manipulations' volumes (a plan made after the grasp, e.g. replanning
    # after every action, routes its moves without knowing where the object was meant to go)
    hard: tuple[Region, ...] = tuple(r for r in hard_regions(goal, held, region) if r.radius > 0)
    in_the_way = any(r.hits_box(spot[PLACE]) for r in hard)
    if unseeable or away or in_the_way or not (
            belief.clear(spot[SPOT], spot[ONLY], belief.params.eps_clear)
            and belief.clear(m.survey or spot[SPOT], spot[ONLY], belief.params.eps_clear)):
        # the planned placement is no longer possible (something is there now, its carry volume
        # cannot be observed from here, or the plan needs that place clear): place it elsewhere from here
        options = []
        for fog_ok, through in ((False, False), (True, False), (True, True)):
            options = _manip_options(belief, held, m.home, hard, tuple(taboo_regions(context)), 2,
                                     fog_ok=fog_ok, through=through, held_at=(at, pc))
            if options:
                break
        if region.radius <= 0:  # only the hand must be emptied: putting it back down is fine too
            back = tuple(reversed(m.pick_path)) if len(m.pick_path) > 1 else (pc, m.home)
            options.append(Manip(held, m.home, pc, at, at, pc, (pc,), (pc,), (pc, *back[1:]),
                                 Region(pc, pc, 0.0)))
    for opt in options:
        # (not the first placement's spot: a new object there is why this one was chosen)
        r_opt = Region(opt.place, opt.place, 0.0) if only_hand else region
        yield {R: r_opt, EX: ex, O: held, EXO: ex | {held}, M: opt, HOME: home,
               PC: opt.pick_conf, **_spot(opt, held, size, belief.geom.robot_radius)}


def _spot(m: Manip, name: str, size: tuple[float, float], radius: float) -> dict[Var, Any]:
    """The placed box and the disc around it that must be free of other objects when it is put down."""
    box = Box(m.place.x, m.place.y, *size)
    return {PLACE: box, SPOT: Region(m.place, m.place, math.hypot(*size) / 2), ONLY: frozenset({name}),
            SURVEY: m.survey, KEEP: kept_regions(m, size, radius)}


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


def _carry_check(
    geom: MapGeometry, box: Box, offset: tuple[float, float], margin: float = 0.0,
) -> Callable[[Pt, Pt], bool]:
    """Exact test of a straight drag: the robot and the swept object box (``margin`` more) stay off the walls."""
    sh = shapely()
    hw, hh = box.w / 2, box.h / 2

    def ok(a: Pt, b: Pt) -> bool:
        if not geom.segment_free(a, b):
            return False
        corners = [(p.x + offset[0] + sx * hw, p.y + offset[1] + sy * hh)
                   for p in (a, b) for sx in (-1, 1) for sy in (-1, 1)]
        return bool(sh.MultiPoint(corners).convex_hull.distance(geom.wall_shape) >= 0.03 + margin)

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
    if not out:  # nowhere in observed space: plan through fog, and look there before placing
        out = _manip_options(belief, name, home, hard, taboo, n, gone, fog_ok=True)
    if not out:  # other objects in the way: plan through them; they are cleared first (NAMO's recursion)
        out = _manip_options(belief, name, home, hard, taboo, n, gone, fog_ok=True, through=True)
    cache[key] = out
    if not out and not gone and len(hard) <= 1 and not taboo and home == belief.nominal():
        # nowhere at all to put it from where the robot is: route around it until something new is seen
        belief.unmovable[name] = belief.percept
    return out


@dataclass
class _Carry:
    """For one pick configuration: where the robot can drag the object to, and at what cost."""

    pc: int
    offset: tuple[float, float]
    carry_free: np.ndarray
    par_c: list[int]
    cells: np.ndarray  # release cells reachable with the object
    cx: np.ndarray  # the object's centre when released there
    cy: np.ndarray
    base_score: np.ndarray  # carry length + return estimate (+ fog penalty)


@dataclass
class _Core:
    """Everything about moving one object from one home that does not depend on the goal."""

    obox: Box
    hc: int
    base: np.ndarray
    base_home: np.ndarray
    free_pick: np.ndarray
    par_pick: list[int]
    carries: list[_Carry]
    returns: dict[tuple[float | None, float | None, int], tuple[list[float], list[int], np.ndarray] | None]


def _core(
    belief: NamoBelief, name: str, home: Pt, gone: frozenset[str], fog_ok: bool, through: bool,
    held_at: tuple[Pt, Pt] | None,
) -> _Core | None:
    key = ("manip-core", name, home, gone, fog_ok, through, held_at)
    cache = belief.cache()
    if key in cache:
        return cache[key]  # type: ignore[no-any-return]
    core = _build_core(belief, name, home, gone, fog_ok, through, held_at)
    cache[key] = core
    return core


def _build_core(
    belief: NamoBelief, name: str, home: Pt, gone: frozenset[str], fog_ok: bool, through: bool,
    held_at: tuple[Pt, Pt] | None,
) -> _Core | None:
    geom, params = belief.geom, belief.params
    g = geom.grid
    r = geom.robot_radius
    est = belief.objects[name]
    obox = est.box if held_at is None else est.box.moved(held_at[0])
    margin = belief.drag_margin.get(name, 0.0)  # learnt from drags of it a wall stopped
    k = k_of(params.eps_clear)
    others = np.zeros(g.n, dtype=bool)
    if not through:
        for o in belief.free_objects({name} | gone):
            others |= g.box_mask(o.box, k * o.sigma)
    base = ~geom.robot_blocked & ~g.dilate(others, r)
    if belief.bumps:
        base[list(belief.bumps)] = False
    if not fog_ok:
        base &= belief.observed
    # the pick happens once the object is localised (BVRelPose), so keep the clearance that needs
    clearance = k * min(est.sigma, params.eps_pick)
    own = g.box_mask(obox, r + clearance)
    hc = g.cell(home)
    free_pick = base & ~own
    free_pick[hc] = True
    dist_pick, par_pick = dijkstra(g, free_pick, hc)
    # grasp from right next to the object: the nearest free cells around it (at most a cell further)
    gap = _box_dist(g, obox)
    ring_cells = [c for c in np.nonzero(free_pick)[0].tolist() if dist_pick[c] < INF]
    if not ring_cells:
        return None
    nearest = min(gap[c] for c in ring_cells)
    pcs = sorted((dist_pick[c], c) for c in ring_cells if gap[c] <= max(nearest, r + clearance) + g.res * 0.75)
    if held_at is not None:  # already grasped: the pick configuration is where the robot is
        pcs = [(0.0, g.cell(held_at[1]))]
    base_home = base.copy()
    base_home[hc] = True
    dist_home = np.asarray(dijkstra(g, base_home, hc)[0])
    # where the object's centre may go: off the walls (exactly) and off other objects; fog costs extra
    # (its own cells count as floor: they are hidden behind its front face)
    hidden_own = g.box_mask(obox, k * est.sigma + g.res)
    obj_ok = ~_dilate_box(g, others, obox.w / 2, obox.h / 2)
    obj_known = ~_dilate_box(g, ~belief.observed & ~hidden_own, obox.w / 2, obox.h / 2)
    carries = []
    for _, pc in pcs[:2]:
        pcp = g.center(pc)
        di = int(round((obox.cx - pcp.x) / g.res))
        dj = int(round((obox.cy - pcp.y) / g.res))
        offset = (obox.cx - pcp.x, obox.cy - pcp.y)
        carry_free = base & _shift_cells(g, obj_ok, di, dj, False) & _box_off_walls(
            geom, obox.w + 2 * margin, obox.h + 2 * margin, *offset)
        carry_free[pc] = True
        dist_c, par_c = dijkstra(g, carry_free, pc)
        dc = np.asarray(dist_c)
        cells = np.nonzero(np.isfinite(dc) & np.isfinite(dist_home))[0]
        cells = cells[(cells != pc) & (cells != hc)]
        cx = np.round(g.xs[cells] + offset[0], 2)
        cy = np.round(g.ys[cells] + offset[1], 2)
        # the placed object must leave room for the robot at home
        dxh = np.maximum(np.abs(cx - home.x) - obox.w / 2, 0.0)
        dyh = np.maximum(np.abs(cy - home.y) - obox.h / 2, 0.0)
        keep = np.hypot(dxh, dyh) > r + 0.05
        cells, cx, cy = cells[keep], cx[keep], cy[keep]
        score = dc[cells] + dist_home[cells]
        oc = cells + dj * g.nx + di
        known = (oc >= 0) & (oc < g.n)
        known[known] = obj_known[oc[known]]
        score = score + np.where(known, 0.0, params.fog_place_cost)
        carries.append(_Carry(pc, offset, carry_free, par_c, cells, cx, cy, score))
    return _Core(obox, hc, base, base_home, free_pick, par_pick, carries, {})


def _hits(region: Region, cx: np.ndarray, cy: np.ndarray, hw: float, hh: float, grow: float) -> np.ndarray:
    """Vectorised :meth:`Region.hits_box` for boxes of half-size (hw, hh) centred at (cx, cy)."""
    a, b = region.start, region.end
    L = region.length
    if L > 1e-9:
        t0 = min(region.radius, L / 2) / L
        a = Pt(a.x + (b.x - a.x) * t0, a.y + (b.y - a.y) * t0)
    n = max(2, int(a.dist(b) / 0.05) + 2)
    ts = np.linspace(0.0, 1.0, n)
    px = a.x + ts * (b.x - a.x)
    py = a.y + ts * (b.y - a.y)
    dx = np.maximum(np.abs(px[None, :] - cx[:, None]) - hw, 0.0)
    dy = np.maximum(np.abs(py[None, :] - cy[:, None]) - hh, 0.0)
    d = np.hypot(dx, dy).min(axis=1)
    return np.asarray(d < region.radius + grow - GRAZE_OK, dtype=bool)


def _manip_options(
    belief: NamoBelief, name: str, home: Pt, hard: tuple[Region, ...], taboo: tuple[Region, ...], n: int,
    gone: frozenset[str] = frozenset(), fog_ok: bool = False, through: bool = False,
    held_at: tuple[Pt, Pt] | None = None,
) -> list[Manip]:
    """Manipulations through observed space, or (``fog_ok``) also through fog, to be surveyed first,
    or (``through``) also through other movable objects, which must be cleared from the carry volume.

    ``held_at`` = (object centre, pick configuration) re-plans the placement of an object already held.
    """
    core = _core(belief, name, home, gone, fog_ok, through, held_at)
    if core is None:
        return []
    geom, params = belief.geom, belief.params
    g = geom.grid
    r = geom.robot_radius
    obox, hc = core.obox, core.hc
    hw, hh = obox.w / 2, obox.h / 2
    results: list[tuple[float, Manip]] = []
    for carry in core.carries:
        if not carry.cells.size:
            continue
        ok = np.ones(carry.cells.size, dtype=bool)
        for h in hard:
            ok &= ~_hits(h, carry.cx, carry.cy, hw, hh, PLACE_MARGIN)
        score = carry.base_score.copy()
        for t in taboo:
            score = score + np.where(_hits(t, carry.cx, carry.cy, hw, hh, PLACE_MARGIN), params.taboo_cost, 0.0)
        idx = np.nonzero(ok)[0]
        order = idx[np.lexsort((carry.cells[idx], score[idx]))]
        found, checks = 0, 0
        rejected: list[Pt] = []
        for i in order.tolist():
            if checks >= 40:
                break
            c = int(carry.cells[i])
            rel = g.center(c)
            if any(rel.dist(q) < 0.35 for q in rejected):
                continue  # next to a placement that cut the robot off: so would this one, most likely
            checks += 1
            box = Box(float(carry.cx[i]), float(carry.cy[i]), obox.w, obox.h)
            ret = _return_path(core, box, c, params.connectivity, r, g)
            if ret is None:
                rejected.append(rel)
                continue
            par_r, free_ret = ret
            # an object already held was picked: there is no pick path left to find (the robot may
            # even stand inside the object's clearance or another object's shadow, which the pick
            # search keeps out of, and which dropped every re-placement of a held object)
            pick_cells = trace_back(core.par_pick, hc, carry.pc) if held_at is None else [carry.pc]
            carry_cells = trace_back(carry.par_c, carry.pc, c)
            ret_cells = trace_back(par_r, hc, c)
            if pick_cells is None or carry_cells is None or ret_cells is None:
                continue
            ret_cells.reverse()
            if held_at is None:
                pick_path = smooth_cells(g, core.free_pick, pick_cells, geom.segment_free)
                pick_path[0] = home
            else:
                pick_path = [held_at[1]]
            ret_path = smooth_cells(g, free_ret, ret_cells, geom.segment_free)
            ret_path[-1] = home
            pcp = g.center(carry.pc)
            survey = Region(pcp, rel, r + math.hypot(obox.w, obox.h) / 2) if fog_ok else Region(pcp, pcp, 0.0)
            m = Manip(
                obj=name, home=home, pick_conf=pcp if held_at is None else held_at[1], obj_at=obox.center,
                place=box.center, release=rel, survey=survey,
                pick_path=tuple(pick_path),
                carry_path=tuple(smooth_cells(g, carry.carry_free, carry_cells,
                                              _carry_check(geom, obox, carry.offset,
                                                           belief.drag_margin.get(name, 0.0)))),
                return_path=tuple(ret_path),
            )
            results.append((float(score[i]), m))
            found += 1
            if found >= n:
                break
    results.sort(key=lambda x: x[0])
    return [m for _, m in results[:n]]


def _connected(g: Grid, free: np.ndarray, a: int, b: int) -> bool:
    """Are cells a and b in one 4-connected component of ``free``?

    The same answer as :func:`~nowplan.domains.namo.paths.dijkstra`'s
    reachability: its diagonal steps need both side cells free, so they never
    connect what 4-neighbour steps do not.  Uses scipy's labelling when scipy
    is installed (it is not a dependency), else says yes and lets the
    Dijkstra search decide.
    """
    if ndimage is None:  # pragma: no cover - scipy present in the development environment
        return True
    labels, _ = ndimage.label(free.reshape(g.ny, g.nx))
    flat = labels.reshape(-1)
    return bool(flat[a] != 0 and flat[a] == flat[b])


def _return_path(
    core: _Core, box: Box, c: int, connectivity: bool, r: float, g: Grid
) -> tuple[list[int], np.ndarray] | None:
    """A way home from release cell ``c`` with the object placed as ``box`` (Fig. 8), memoised."""
    key = (box.cx, box.cy, c) if connectivity else (None, None, c)
    if key in core.returns:
        hit = core.returns[key]
        return None if hit is None else (hit[1], hit[2])
    if connectivity:
        free_ret = core.base & ~(_box_dist(g, box) < r - 0.01)  # exactly: the robot was released next to it
        free_ret[core.hc] = True
        free_ret[c] = True
    else:  # the check of Fig. 8 switched off: the placed object is ignored
        free_ret = core.base_home
    if not _connected(g, free_ret, core.hc, c):  # most rejections: no Dijkstra for them
        core.returns[key] = None
        return None
    dist_r, par_r = dijkstra(g, free_ret, core.hc, target=c)
    if dist_r[c] == INF:
        core.returns[key] = None
        return None
    core.returns[key] = (dist_r, par_r, free_ret)
    return par_r, free_ret
