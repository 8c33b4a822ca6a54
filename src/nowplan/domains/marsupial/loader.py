"""The loader's motion planner: A* over a cargo bay's configurations (seed 002 V-B).

A configuration is a :class:`~nowplan.domains.marsupial.grid.Hold` with the
package placed at the load anchor.  Its successors are the seed's robot
operators, each of cost 1: ``LoaderMove`` (walk to a cell it can reach
through free cells), ``LoaderGrasp`` (lift a neighbouring package) and
``LoaderPlace`` (set the held package down on free cells next to the
loader: in storage, exactly at the load anchor, or in the load region as a
temporary buffer).  Placements are tried in the greedy packer's order of
preference, which also breaks ties between equally cheap solutions, so
stowed packages go towards the back and the sides.

Three searches serve the domain's generators: *stow* (the vehicle packed),
*fetch p* (``p`` alone at the load anchor, ready to unload) and *exact* (a
given configuration, for regression through a path already found).  Found
paths are cached, so regression from the end of a path back to the current
configuration costs one search.
"""

from __future__ import annotations

import heapq
import itertools
import logging
from collections.abc import Callable, Mapping, Sequence
from functools import lru_cache
from typing import Any, NamedTuple

from nowplan.domains.marsupial import bitgrid as bg
from nowplan.domains.marsupial.grid import (
    STEPS,
    Cell,
    Door,
    Hold,
    border,
    cells,
    door_status,
    in_storage,
    is_packed,
    load_anchor,
    occupancy,
    placement_penalty,
    stored,
)

log = logging.getLogger(__name__)

Config = tuple[Hold, Door]
EPS = 1e-3  # weight of the packer's placement preference in the search cost
MAX_PLACEMENTS = 6  # storage spots the loader walks towards per held package (best first)
MAX_BUFFER = 2  # temporary spots in the load region it walks towards
# configurations a search with an infeasibility test expands before asking it (PathCache.path; the
# answer is the search's either way, the probe only decides when the test is worth its cost): the
# fetch searches that fail expand 20 000; of those that succeed in seed 002's full run all but 4
# end within 1 000 and 3 of the 4 within 1 150 (both dispersed; one took 6 413), where the test,
# which could not prove them impossible, cost 0.07-0.21 CPU s each
PROBE_NODES = 2_000
SEARCH_NODES = 20_000  # configurations a search closes at most


class Transition(NamedTuple):
    """One robot operator: ``kind`` is move/grasp/place, ``arg`` the target cell or package
    (a named tuple, as :class:`~.grid.Hold`: one is made per successor the searches generate)."""

    kind: str
    arg: object
    before: Config
    after: Config

    @property
    def door_before(self) -> str:
        return door_status(*self.before)

    @property
    def door_after(self) -> str:
        return door_status(*self.after)


@lru_cache(maxsize=8192)
def spot_penalty(shape: str, anchor: Cell, rows: int, cols: int) -> float:
    """Spots by the packer's preference; the load anchor first, the load-region buffer last."""
    if anchor == load_anchor(cols):
        return -1.0
    pen = placement_penalty(shape, anchor, rows)
    return pen if stored(shape, anchor, rows, cols) else pen + 10.0 * cols


@lru_cache(maxsize=256)
def _anchors(shape: str, rows: int, cols: int) -> tuple[tuple[Cell, tuple[Cell, ...]], ...]:
    """The anchors where ``shape`` lies inside the grid, with its cells there (row-major)."""
    out = []
    for r in range(rows):
        for c in range(cols):
            cs = cells(shape, (r, c))
            if all(0 <= x[0] < rows and 0 <= x[1] < cols for x in cs):
                out.append(((r, c), cs))
    return tuple(out)


def spots(hold: Hold, door: Door, shape: str) -> list[Cell]:
    """Anchors where ``shape`` can be set down on free cells (the load anchor only if the door is free)."""
    occ = occupancy(hold, door).keys()
    loader, anchor = hold.loader, load_anchor(hold.cols)
    out = []
    for a, cs in _anchors(shape, hold.rows, hold.cols):
        if loader not in cs and occ.isdisjoint(cs):
            if a == anchor or door is None or anchor not in cs:
                out.append(a)
    return out


def _set_down(hold: Hold, door: Door, anchor: Cell) -> Config:
    assert hold.held is not None and hold.held_shape is not None
    base = Hold(hold.rows, hold.cols, hold.items, hold.loader, None, None)
    if anchor == load_anchor(hold.cols) and door is None:
        return base, (hold.held, hold.held_shape)
    return base.with_items([*hold.items, (hold.held, hold.held_shape, anchor)]), door


# what the successors of a configuration share with every configuration that differs from it only in
# the loader's cell (the occupied cells, the cells next to them, the spots for the held package)
_Shared = tuple[dict[Cell, str], int, int, tuple[tuple[float, Cell, int, int], ...]]


def _shared(hold: Hold, door: Door) -> _Shared:
    rows, cols = hold.rows, hold.cols
    occ = occupancy(hold, door)
    occ_mask = bg.mask(occ, rows, cols)
    lay = bg.layout(rows, cols)
    ranked: tuple[tuple[float, Cell, int, int], ...] = ()
    if hold.held_shape is not None:
        shape = hold.held_shape
        anchor = load_anchor(cols)
        found = []
        for a, cs in _anchors(shape, rows, cols):  # spots(), but for the loader's cell (see successors)
            if occ.keys().isdisjoint(cs) and (a == anchor or door is None or anchor not in cs):
                found.append((spot_penalty(shape, a, rows, cols), a, bg.shape_mask(shape, a, rows, cols),
                              bg.border_mask(shape, a, rows, cols)))
        ranked = tuple(sorted(found))
    return occ, occ_mask, bg.expand(occ_mask, lay), ranked


def successors(conf: Config, memo: dict[Any, _Shared] | None = None) -> list[tuple[Transition, float]]:
    """The robot operators from ``conf``, made anew at each call.  (A memo of them, 4,096
    configurations, hit 13 % of the calls across the 24 RCHPN runs of both-dispersed 5-10, trials 0-3,
    and the ~108,000 objects it kept made every pass of the cyclic collector dearer than the hits
    saved, docs/peephole.md.)  ``memo`` (one search's) keeps what configurations that differ only in
    the loader's cell share: the occupied cells, the cells next to them and the held package's spots;
    the loader's walk is a flood over bit masks (:mod:`.bitgrid`).  The operators and their order are
    those of :func:`~.grid.reachable` and :func:`spots` (tests/test_rchpn_overhead.py)."""
    hold, door = conf
    rows, cols = hold.rows, hold.cols
    key = (hold.items, door, hold.held, hold.held_shape)
    shared = memo.get(key) if memo is not None else None
    if shared is None:
        shared = _shared(hold, door)
        if memo is not None:
            memo[key] = shared
    occ, occ_mask, near_mask, ranked_all = shared
    lay = bg.layout(rows, cols)
    loader = hold.loader
    lbit = bg.mask((loader,), rows, cols)
    layers = bg.flood(lbit, lay.full & ~occ_mask, lay)
    reach = 0
    for layer in layers:
        reach |= layer
    out: list[tuple[Transition, float]] = []
    if hold.held is None:
        seen: set[str] = set()
        for dr, dc in STEPS:  # lift a neighbouring package
            q = occ.get((loader[0] + dr, loader[1] + dc))
            if q is None or q in seen:
                continue
            seen.add(q)
            if door is not None and q == door[0]:
                after: Config = (Hold(hold.rows, hold.cols, hold.items, hold.loader, q, door[1]), None)
            else:
                q_shape = next(s for n, s, _ in hold.items if n == q)
                rest = tuple(sorted(i for i in hold.items if i[0] != q))
                after = (Hold(hold.rows, hold.cols, rest, hold.loader, q, q_shape), door)
            out.append((Transition("grasp", q, conf, after), 1.0))
        # walk next to a package, or out of the load region (to the nearest storage cell)
        targets = set(bg.cells_of(reach & near_mask & ~lbit, cols))
        if not in_storage(loader, rows, cols):
            park = bg.nearest(lay.storage, layers, cols)
            if park is not None:
                targets.add(park)
        for x in sorted(targets):
            out.append((Transition("move", x, conf, (_moved(hold, x), door)), 1.0))
        return out
    # the spots free of the loader's cell (spots()), best first
    ranked = [(pen, a, bm) for pen, a, sm, bm in ranked_all if not sm & lbit]
    for pen, a, bm in ranked:  # set it down next to the loader (never on it)
        if bm & lbit:
            out.append((Transition("place", hold.held, conf, _set_down(hold, door, a)), 1.0 + EPS * max(pen, 0.0)))
    # walk towards the best spots (each from its nearest neighbouring cell)
    stores = [bm for p, _, bm in ranked if p < 10.0 * cols][:MAX_PLACEMENTS]
    buffers = [bm for p, _, bm in ranked if p >= 10.0 * cols][:MAX_BUFFER]
    targets = set()
    for bm in stores + buffers:
        if not bm & lbit:
            stand = bg.nearest(bm, layers, cols)
            if stand is not None:
                targets.add(stand)
    for x in sorted(targets):
        out.append((Transition("move", x, conf, (_moved(hold, x), door)), 1.0))
    return out


def _moved(hold: Hold, x: Cell) -> Hold:
    """``hold`` with the loader at ``x``."""
    return Hold(hold.rows, hold.cols, hold.items, x, hold.held, hold.held_shape)


Goal = Callable[[Config], bool]
Heuristic = Callable[[Config], float]


def stow_goal(conf: Config) -> bool:
    return is_packed(*conf)


def stow_h(conf: Config) -> float:
    """An admissible and consistent estimate of the stow cost (every operator costs at least 1).

    A grasp and a place for the package at the door and for each one in the load region, a
    place for the held one, and one move if the loader must walk at all: it stands in the load
    region (it ends in storage), or it must grasp the package at the door and is not next to it
    (grasps and places never move the loader, so either needs a move of its own; at most one is
    counted, as one move may serve both).
    """
    hold, door = conf
    rows, cols = hold.rows, hold.cols
    h = 2.0 if door is not None else 0.0
    h += 1.0 if hold.held is not None else 0.0
    h += sum(2.0 for _, s, a in hold.items if not stored(s, a, rows, cols))
    if not in_storage(hold.loader, rows, cols):
        h += 1.0
    elif door is not None and hold.loader not in border(door[1], load_anchor(cols)):
        h += 1.0
    return h


def fetch_goal(pkg: str) -> Goal:
    return lambda conf: conf[0].held is None and door_status(*conf) == pkg


def fetch_h(pkg: str) -> Heuristic:
    """An admissible and consistent estimate of the cost of fetching ``pkg`` to the load anchor.

    A grasp and a place for every other package in the load region or at the door, a place for
    ``pkg`` (and a grasp unless it is held), a place for another package held, and the moves
    those need at least: a held ``pkg`` is set down from a cell next to its spot at the anchor,
    so a loader elsewhere must walk; a ``pkg`` in the bay is grasped from a cell next to it (a
    loader elsewhere must walk there) and, if no cell touches both it and its spot at the
    anchor, the loader walks again between the grasp and the place.  (A plan that grasps ``pkg``
    twice pays a grasp and a place more than these two moves.)
    """
    def h(conf: Config) -> float:
        hold, door = conf
        rows, cols = hold.rows, hold.cols
        blocking = 0.0
        mine: tuple[str, Cell] | None = None
        for n, s, a in hold.items:
            if n == pkg:
                mine = (s, a)
            elif not stored(s, a, rows, cols):
                blocking += 2.0
        if door is not None and door[0] == pkg:
            # a held package is set down, and a loader in the load region walks out (before, one
            # operator was counted for either, which with a package to clear from the load
            # region dropped by 2 over one grasp: not consistent)
            held = 1.0 if hold.held is not None else 0.0
            return blocking + held + (0.0 if in_storage(hold.loader, rows, cols) else 1.0)
        out = blocking + (2.0 if door is not None else 0.0)
        if hold.held == pkg:
            assert hold.held_shape is not None
            return out + 1.0 + (0.0 if hold.loader in border(hold.held_shape, load_anchor(cols)) else 1.0)
        out += 2.0
        if mine is not None:
            near = border(*mine)
            if hold.held is not None:
                out += 1.0  # another package held: it is set down first
            if hold.loader not in near:
                out += 1.0
            if near.isdisjoint(border(mine[0], load_anchor(cols))):
                out += 1.0
        return out

    return h


def exact_goal(target: Hold, status: str | None) -> Goal:
    return lambda conf: conf[0] == target and (status is None or door_status(*conf) == status)


def search(
    start: Config, goal: Goal, h: Heuristic, max_nodes: int = SEARCH_NODES, weight: float = 1.0
) -> list[Transition] | None:
    """Weighted A* over configurations: a cheap operator sequence reaching ``goal``, or None."""
    return search_status(start, goal, h, max_nodes, weight)[0]


def search_status(
    start: Config, goal: Goal, h: Heuristic, max_nodes: int = SEARCH_NODES, weight: float = 1.0
) -> tuple[list[Transition] | None, bool]:
    """:func:`search`, and whether it stopped at ``max_nodes`` (False: it found a path or
    expanded every configuration it can reach)."""
    return AStar(start, goal, h, weight).run(max_nodes)


class AStar:
    """The loader's weighted A*, resumable: :meth:`run` with a larger limit after one that stopped
    at its limit goes on where it stopped, so it expands what one run with that limit would, in the
    same order, and gives the same answer (:meth:`PathCache.path` probes with a small limit first)."""

    def __init__(self, start: Config, goal: Goal, h: Heuristic, weight: float = 1.0) -> None:
        self.goal, self.h, self.weight = goal, h, weight
        self._counter = itertools.count()
        self._frontier: list[tuple[float, int, Config]] = [(h(start), next(self._counter), start)]
        # per configuration reached: [cost so far, the transition into it, closed] (one dict: a
        # configuration is hashed once per successor instead of once per table)
        self._node: dict[Config, list[Any]] = {start: [0.0, None, False]}
        self.closed = 0
        self._shared: dict[Any, _Shared] = {}  # what configurations differing only in the loader's cell share

    def run(self, max_nodes: int) -> tuple[list[Transition] | None, bool]:
        """Search on until a path is found (it, False), every reachable configuration is closed
        (None, False) or more than ``max_nodes`` configurations in all would be closed (None, True)."""
        frontier, node, goal, h, weight = self._frontier, self._node, self.goal, self.h, self.weight
        counter, shared = self._counter, self._shared
        while frontier:
            entry = heapq.heappop(frontier)
            conf = entry[2]
            rec = node[conf]
            if rec[2]:
                continue
            if goal(conf):
                path: list[Transition] = []
                t = rec[1]
                while t is not None:
                    path.append(t)
                    t = node[t.before][1]
                path.reverse()
                return path, False
            if self.closed >= max_nodes:
                heapq.heappush(frontier, entry)  # the next to close, when a larger limit resumes
                log.info("loader search gave up after %d configurations", max_nodes)
                return None, True
            rec[2] = True
            self.closed += 1
            g = rec[0]
            for t, cost in successors(conf, shared):
                nxt = t.after
                ng = g + cost
                known = node.get(nxt)
                if known is None:
                    node[nxt] = [ng, t, False]
                elif known[2] or ng >= known[0]:
                    continue
                else:
                    known[0] = ng
                    known[1] = t
                heapq.heappush(frontier, (ng + weight * h(nxt), next(counter), nxt))
        return None, False


class PathCache:
    """Paths found from each start configuration, so regression can walk back along them."""

    def __init__(self, limit: int = 4096) -> None:
        self.limit = limit
        self._paths: dict[tuple[Config, str], list[Transition] | None] = {}
        # the paths from each start, in the order they were found (``into`` reads one start's
        # paths only; scanning every cached path made it the loader's costliest call under RCHPN)
        self._by_start: dict[Config, list[list[Transition]]] = {}
        # the keys whose ``None`` is a proof (every configuration reachable closed, or the
        # infeasibility test), not a search stopped at its limit
        self._impossible: set[tuple[Config, str]] = set()
        self.searches = 0
        self.relaxed_tests = 0  # searches that asked their infeasibility test, and were cut by it
        self.relaxed_proofs = 0

    def path(
        self, start: Config, mode: str, goal: Goal, h: Heuristic,
        infeasible: Callable[[Config], bool] | None = None,
    ) -> list[Transition] | None:
        """The search's path for ``mode`` from ``start`` (cached).  With ``infeasible`` (a test that
        answers True only where the search must fail, e.g. :func:`.bay_relaxed.fetch_infeasible`),
        a search that has not ended after :data:`PROBE_NODES` configurations asks the test, and
        stops if it says so; the answer is always the full search's."""
        key = (start, mode)
        if key not in self._paths:
            if len(self._paths) >= self.limit:
                self._paths.clear()
                self._by_start.clear()
                self._impossible.clear()
            self.searches += 1
            if infeasible is None:
                found, cut = search_status(start, goal, h)
            else:
                astar = AStar(start, goal, h)
                found, cut = astar.run(PROBE_NODES)
                if cut:
                    self.relaxed_tests += 1
                    if infeasible(start):
                        self.relaxed_proofs += 1
                        cut = False
                    else:
                        found, cut = astar.run(SEARCH_NODES)  # on from where the probe stopped
            self._paths[key] = found
            if found is None and not cut:
                self._impossible.add(key)
            if found:
                self._by_start.setdefault(start, []).append(found)
        return self._paths[key]

    def impossible(self, start: Config, mode: str) -> bool:
        """Did :meth:`path` for ``mode`` from ``start`` prove that no path exists (False: it found
        one, stopped at its limit, or was not asked)?"""
        return (start, mode) in self._impossible

    def into(self, start: Config, target: Hold, status: str | None) -> Transition | None:
        """The transition of a known path from ``start`` that ends in ``target``."""
        for known in self._by_start.get(start, ()):
            for t in known:
                if t.after[0] == target and (status is None or t.door_after == status):
                    return t
        p = self.path(start, f"exact:{target}:{status}", exact_goal(target, status), lambda c: 0.0)
        return p[-1] if p else None


CACHE = PathCache()


def door_of(status: str, shapes: Mapping[str, str]) -> Door:
    from nowplan.domains.marsupial.grid import door_package

    pkg = door_package(status)
    return (pkg, shapes[pkg]) if pkg is not None else None


def can_stow_in_turn(hold: Hold, door: Door, extra: Sequence[tuple[str, str]]) -> bool:
    """Can the loader stow ``extra`` packages, loaded in this order, into the bay as it is now?

    The shareability test of the loads as the robot will do them: each
    package arrives at the load anchor and the stow search (the one the
    ``door(v) = none`` and ``packed(v)`` generators use) must find a way to
    put it in storage from where the earlier ones were put.  The greedy
    packer (:func:`~.grid.can_share`) may find room that this loader, placing
    each package cheaply, does not leave; this test follows the loader.
    Paths come from (and go into) :data:`CACHE`, so the plan that follows a
    positive answer reuses them.
    """
    key = (hold, door, tuple(extra))
    known = _STOW_MEMO.get(key)
    if known is not None:
        return known
    conf: Config = (hold, door)
    ok = True
    have = set(hold.packages()) | ({door[0]} if door is not None else set())
    todo = [(n, s) for n, s in extra if n not in have]
    for i in range(len(todo) + 1):
        if not is_packed(*conf):
            path = CACHE.path(conf, "stow", stow_goal, stow_h)
            if not path:
                ok = False
                break
            conf = path[-1].after
        if i < len(todo):
            conf = (conf[0], todo[i])
    if len(_STOW_MEMO) >= 4096:
        _STOW_MEMO.clear()
    _STOW_MEMO[key] = ok
    return ok


_STOW_MEMO: dict[tuple[Hold, Door, tuple[tuple[str, str], ...]], bool] = {}
