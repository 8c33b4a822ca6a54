"""Cargo bays of the marsupial logistics domain: a grid, Tetris-like packages, a loader robot.

Every vehicle's cargo area is a ``rows × cols`` grid (3×6 or 4×8, seed 002
V-B).  The two columns at the door (the right-hand side) are the *load
region*; a package is loaded onto, and unloaded from, the *load anchor* —
the top-left of the load region.  The other columns are the *storage
region*: a vehicle may travel only when every package and the loader are in
storage (it is *packed*).  The loader occupies one cell and walks in the four
directions through free cells; it grasps a package from a neighbouring cell
and lifts it (a forklift), so a held package covers no cells until the loader
sets it down on free cells next to itself.

:class:`Hold` is the value of the ``cargo(v)`` fluent: the packages set down
in the grid except one *placed at the load anchor* (that one is the
``door(v)`` fluent), the loader's cell and the package it holds.  The
functions here are the geometry (cells, occupancy, where the loader can
walk) and the seed's greedy packer: packages go as far towards the back as
possible, towards the sides as a tie-breaker.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable, Mapping, Sequence
from functools import lru_cache
from typing import NamedTuple

Cell = tuple[int, int]  # (row, column); row 0 at the top, the door on the right

# six Tetris-like shapes (cells relative to the top-left of their bounding box); at most two
# columns wide, so each fits the two-column load region
SHAPES: dict[str, tuple[Cell, ...]] = {
    "dot": ((0, 0),),
    "bar": ((0, 0), (0, 1)),
    "pole": ((0, 0), (1, 0)),
    "tall": ((0, 0), (1, 0), (2, 0)),
    "ell": ((0, 0), (1, 0), (1, 1)),
    "box": ((0, 0), (0, 1), (1, 0), (1, 1)),
}
SIZES = ((3, 6), (4, 8))  # small and large cargo areas
STEPS: tuple[Cell, ...] = ((-1, 0), (1, 0), (0, -1), (0, 1))
NONE = "none"  # door(v) when the load region is free
BUSY = "busy"  # door(v) when something else is in the load region


@lru_cache(maxsize=4096)
def cells(shape: str, anchor: Cell) -> tuple[Cell, ...]:
    r, c = anchor
    return tuple((r + dr, c + dc) for dr, dc in SHAPES[shape])


@lru_cache(maxsize=4096)
def border(shape: str, anchor: Cell) -> frozenset[Cell]:
    """The cells next to ``shape`` set down at ``anchor`` (outside it; may lie off the grid)."""
    cs = cells(shape, anchor)
    return frozenset((r + dr, c + dc) for r, c in cs for dr, dc in STEPS) - frozenset(cs)


def load_anchor(cols: int) -> Cell:
    return (0, cols - 2)


def in_storage(cell: Cell, rows: int, cols: int) -> bool:
    return 0 <= cell[0] < rows and 0 <= cell[1] < cols - 2


@lru_cache(maxsize=4096)
def stored(shape: str, anchor: Cell, rows: int, cols: int) -> bool:
    """Does ``shape`` set down at ``anchor`` lie wholly in storage (memoised: the loader's
    heuristics and goal tests ask it for every package of every configuration)?"""
    return all(in_storage(c, rows, cols) for c in cells(shape, anchor))


def inside(cell: Cell, rows: int, cols: int) -> bool:
    return 0 <= cell[0] < rows and 0 <= cell[1] < cols


def adjacent(a: Cell, b: Cell) -> bool:
    return abs(a[0] - b[0]) + abs(a[1] - b[1]) == 1


class Hold(NamedTuple):
    """The value of ``cargo(v)``: packages set down ``(name, shape, anchor)``, the loader, the held one.

    A named tuple (it was a frozen dataclass): the loader's searches make ~5 of these per
    configuration they expand, and a tuple is built, hashed and compared in C (the same hash,
    equality and order as the dataclass had; the replayed searches of 24 RCHPN runs took
    17 % less CPU, docs/peephole.md)."""

    rows: int
    cols: int
    items: tuple[tuple[str, str, Cell], ...] = ()
    loader: Cell = (0, 0)
    held: str | None = None
    held_shape: str | None = None

    @staticmethod
    def empty(rows: int, cols: int) -> Hold:
        return Hold(rows, cols, (), (rows - 1, cols - 3))

    def anchor_of(self, pkg: str) -> Cell | None:
        return next((a for n, _, a in self.items if n == pkg), None)

    def packages(self) -> list[str]:
        return [n for n, _, _ in self.items] + ([self.held] if self.held else [])

    def with_items(self, items: Iterable[tuple[str, str, Cell]]) -> Hold:
        return Hold(self.rows, self.cols, tuple(sorted(items)), self.loader, self.held, self.held_shape)

    def stored(self) -> bool:
        """Every package set down lies in storage."""
        rows, cols = self.rows, self.cols
        return all(stored(s, a, rows, cols) for _, s, a in self.items)

    def __str__(self) -> str:
        body = " ".join(f"{n}@{a[0]}.{a[1]}" for n, _, a in self.items)
        held = f" holding {self.held}" if self.held else ""
        return f"[{body}{' ' if body else ''}loader@{self.loader[0]}.{self.loader[1]}{held}]"


Door = tuple[str, str] | None  # the package placed at the load anchor, with its shape


def occupancy(hold: Hold, door: Door) -> dict[Cell, str]:
    """Which package covers each cell (a held package covers none)."""
    occ: dict[Cell, str] = {}
    for name, shape, anchor in hold.items:
        for c in cells(shape, anchor):
            occ[c] = name
    if door is not None:
        for c in cells(door[1], load_anchor(hold.cols)):
            occ[c] = door[0]
    return occ


def door_status(hold: Hold, door: Door) -> str:
    """The ``door(v)`` fluent: ``none``, the placed package's name, ``busy`` or ``busy:<name>``.

    The load region is busy while the loader stands in it, another package
    covers part of it, or the loader is carrying a package.
    """
    lc = hold.cols - 2
    other = (
        hold.held is not None
        or hold.loader[1] >= lc
        or any(c[1] >= lc for _, s, a in hold.items for c in cells(s, a))
    )
    if door is None:
        return BUSY if other else NONE
    return f"{BUSY}:{door[0]}" if other else door[0]


def door_package(status: str) -> str | None:
    if status in (NONE, BUSY):
        return None
    return status.split(":", 1)[1] if status.startswith(BUSY + ":") else status


def is_packed(hold: Hold, door: Door) -> bool:
    """Every package and the loader in storage, nothing held: the vehicle may travel."""
    return (
        door is None
        and hold.held is None
        and in_storage(hold.loader, hold.rows, hold.cols)
        and hold.stored()
    )


@lru_cache(maxsize=16)
def neighbours(rows: int, cols: int) -> dict[Cell, tuple[Cell, ...]]:
    """Each cell's neighbours inside a ``rows × cols`` grid, in the order of :data:`STEPS`."""
    return {
        (r, c): tuple((r + dr, c + dc) for dr, dc in STEPS if inside((r + dr, c + dc), rows, cols))
        for r in range(rows) for c in range(cols)
    }


def reachable(hold: Hold, door: Door, occ: Mapping[Cell, str] | None = None) -> dict[Cell, int]:
    """Cells the loader can walk to through free cells, with their BFS distance (``occ``: the
    bay's :func:`occupancy`, when the caller has it)."""
    if occ is None:
        occ = occupancy(hold, door)
    nbrs = neighbours(hold.rows, hold.cols)
    start = hold.loader
    dist = {start: 0}
    queue = deque([start])
    while queue:
        x = queue.popleft()
        d = dist[x] + 1
        near = nbrs.get(x)
        if near is None:  # off the grid (never for a loader the operators moved)
            near = tuple(y for y in ((x[0] + dr, x[1] + dc) for dr, dc in STEPS) if inside(y, hold.rows, hold.cols))
        for y in near:
            if y not in dist and y not in occ:
                dist[y] = d
                queue.append(y)
    return dist


def placement_penalty(shape: str, anchor: Cell, rows: int) -> float:
    """The packer's preference: towards the back (column 0), then towards the sides."""
    cs = cells(shape, anchor)
    top = min(r for r, _ in cs)
    bottom = max(r for r, _ in cs)
    side = min(top, rows - 1 - bottom)
    return anchor[1] + 0.1 * side + 0.01 * anchor[0]


def greedy_pack(
    rows: int, cols: int, fixed: Iterable[Cell], shapes: Sequence[str], free_margin: int = 2
) -> list[Cell] | None:
    """Storage anchors for ``shapes`` placed one by one as far back as possible, or None.

    ``fixed`` are cells already taken; at least ``free_margin`` storage cells
    must stay free for the loader to work.  Larger shapes are placed first.
    """
    taken = set(fixed)
    order = sorted(range(len(shapes)), key=lambda i: -len(SHAPES[shapes[i]]))
    out: dict[int, Cell] = {}
    for i in order:
        best: tuple[float, Cell] | None = None
        for r in range(rows):
            for c in range(cols - 2):
                cs = cells(shapes[i], (r, c))
                if all(in_storage(x, rows, cols) and x not in taken for x in cs):
                    key = (placement_penalty(shapes[i], (r, c), rows), (r, c))
                    if best is None or key < best:
                        best = key
        if best is None:
            return None
        out[i] = best[1]
        taken.update(cells(shapes[i], best[1]))
    free = rows * (cols - 2) - sum(1 for x in taken if in_storage(x, rows, cols))
    if free < free_margin:
        return None
    return [out[i] for i in range(len(shapes))]


def can_share(hold: Hold, door: Door, extra: Mapping[str, str], free_margin: int = 2) -> bool:
    """Seed 002's shareability test: can the vehicle be packed with ``extra`` packages too?

    The packages already in storage stay where they are; the others (at the
    door, held, in the load region) and the extra ones are packed greedily
    into the free storage cells.
    """
    rows, cols = hold.rows, hold.cols
    todo: dict[str, str] = {}
    fixed: list[Cell] = []
    for n, s, a in hold.items:
        cs = cells(s, a)
        if all(in_storage(c, rows, cols) for c in cs):
            fixed.extend(cs)
        else:
            todo[n] = s
    if door is not None:
        todo[door[0]] = door[1]
    if hold.held is not None and hold.held_shape is not None:
        todo[hold.held] = hold.held_shape
    have = set(hold.packages()) | set(todo)
    todo.update({p: s for p, s in extra.items() if p not in have})
    return greedy_pack(rows, cols, fixed, list(todo.values()), free_margin) is not None
