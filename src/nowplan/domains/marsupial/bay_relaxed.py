"""A cheap proof that the loader cannot fetch a package: the bay search with the loader's cell
forgotten (seed 002 V-B's robot, relaxed).

The loader's search (:mod:`.loader`) tells configurations apart by the loader's cell, so a bay
where the package cannot be dug out is proved so only after every configuration — every
arrangement of the packages times every cell the loader can stand on — was expanded (20 000
and more on a 3×6 bay with two tall packages).  Here a state keeps only the *region* the loader
can walk in (the free cells connected to its cell) instead of the cell, and every operator the
loader could apply from *some* cell of the region is allowed:

* grasp a package next to any cell of the region (the loader walks there first);
* set the held package down on free cells next to any cell of the region that it does not
  cover, the loader then standing on that cell (one successor per distinct region after);
* the goal: the package alone at the load anchor, nothing held, no other package in the load
  region, and a storage cell in the region (the loader walks out of the load region).

Every configuration the loader's search reaches maps to a state reached here (its moves stay in
the region; its grasps and places are among those allowed here), and each of its goal
configurations to a goal state, so when no goal state is reachable here, the loader's search
cannot succeed either (tested against it on random bays, ``tests/test_marsupial_bay_relaxed.py``).
The converse does not hold: a reachable goal state here says nothing, and the loader searches.
"""

from __future__ import annotations

from collections import deque

from nowplan.domains.marsupial.grid import (
    Cell,
    Door,
    Hold,
    border,
    cells,
    in_storage,
    load_anchor,
    occupancy,
    reachable,
)

# (packages set down, package at the anchor, held package and its shape, the loader's region)
State = tuple[tuple[tuple[str, str, Cell], ...], Door, str | None, str | None, frozenset[Cell]]


def _region(rows: int, cols: int, items: tuple[tuple[str, str, Cell], ...], door: Door, at: Cell) -> frozenset[Cell]:
    return frozenset(reachable(Hold(rows, cols, items, at), door))


def _goal(state: State, pkg: str, rows: int, cols: int) -> bool:
    items, door, held, _, region = state
    if held is not None or door is None or door[0] != pkg:
        return False
    lc = cols - 2
    if any(c[1] >= lc for _, s, a in items for c in cells(s, a)):
        return False
    return any(in_storage(x, rows, cols) for x in region)


def _successors(state: State, rows: int, cols: int) -> list[State]:
    items, door, held, held_shape, region = state
    occ = occupancy(Hold(rows, cols, items), door)
    out: list[State] = []
    if held is None:
        near: set[str] = set()
        for x in region:
            for dr, dc in ((-1, 0), (1, 0), (0, -1), (0, 1)):
                q = occ.get((x[0] + dr, x[1] + dc))
                if q is not None:
                    near.add(q)
        for q in sorted(near):
            if door is not None and q == door[0]:
                new_items, new_door, shape = items, None, door[1]
            else:
                shape = next(s for n, s, _ in items if n == q)
                new_items, new_door = tuple(i for i in items if i[0] != q), door
            at = min(region)
            out.append((new_items, new_door, q, shape, _region(rows, cols, new_items, new_door, at)))
        return out
    assert held_shape is not None
    anchor = load_anchor(cols)
    taken = occ.keys()
    for r in range(rows):
        for c in range(cols):
            a = (r, c)
            cs = cells(held_shape, a)
            if not all(0 <= x[0] < rows and 0 <= x[1] < cols for x in cs) or not taken.isdisjoint(cs):
                continue
            if not (a == anchor or door is None or anchor not in cs):
                continue
            stands = [y for y in border(held_shape, a) if y in region and y not in cs]
            if not stands:
                continue
            if a == anchor and door is None:
                new_items, new_door = items, (held, held_shape)
            else:
                new_items, new_door = tuple(sorted([*items, (held, held_shape, a)])), door
            seen: set[Cell] = set()
            for y in sorted(stands):
                if y in seen:
                    continue
                reg = _region(rows, cols, new_items, new_door, y)
                seen |= reg
                out.append((new_items, new_door, None, None, reg))
    return out


def fetch_infeasible(hold: Hold, door: Door, pkg: str, max_states: int = 20_000) -> bool:
    """True only if no sequence of loader operators from ``(hold, door)`` puts ``pkg`` alone at the
    load anchor (the loader's fetch search would fail); False when it may (or ``max_states``
    relaxed states were not enough to tell)."""
    rows, cols = hold.rows, hold.cols
    items = tuple(sorted(hold.items))
    start: State = (
        items, door, hold.held, hold.held_shape,
        _region(rows, cols, items, door, hold.loader),
    )
    seen = {start}
    queue = deque([start])
    while queue:
        s = queue.popleft()
        if _goal(s, pkg, rows, cols):
            return False
        for t in _successors(s, rows, cols):
            if t not in seen:
                if len(seen) >= max_states:
                    return False
                seen.add(t)
                queue.append(t)
    return True
