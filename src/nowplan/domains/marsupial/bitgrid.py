"""A cargo bay's cells as bits of an int, for the loader's successor function (:mod:`.loader`).

Cell ``(r, c)`` of a ``rows × cols`` bay is bit ``r * cols + c``, so the bits of a mask in
ascending order are its cells in row-major (sorted) order, and the lowest bit of a mask is its
least cell.  The loader's walk is a breadth-first flood over the free cells, one layer (the cells
at one distance) per mask: a few integer operations per layer instead of a queue and a dict per cell.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from functools import lru_cache
from typing import NamedTuple

from nowplan.domains.marsupial.grid import Cell, border, cells


class Layout(NamedTuple):
    rows: int
    cols: int
    full: int  # every cell
    not_first: int  # cells not in column 0 (they have a left neighbour)
    not_last: int  # cells not in the last column (they have a right neighbour)
    storage: int  # the storage region (every column but the two at the door)


@lru_cache(maxsize=16)
def layout(rows: int, cols: int) -> Layout:
    full = (1 << (rows * cols)) - 1
    not_first = not_last = storage = 0
    for r in range(rows):
        for c in range(cols):
            b = 1 << (r * cols + c)
            if c > 0:
                not_first |= b
            if c < cols - 1:
                not_last |= b
            if c < cols - 2:
                storage |= b
    return Layout(rows, cols, full, not_first, not_last, storage)


def mask(cs: Iterable[Cell], rows: int, cols: int) -> int:
    """The cells of ``cs`` that lie inside the bay."""
    out = 0
    for r, c in cs:
        if 0 <= r < rows and 0 <= c < cols:
            out |= 1 << (r * cols + c)
    return out


@lru_cache(maxsize=8192)
def shape_mask(shape: str, anchor: Cell, rows: int, cols: int) -> int:
    return mask(cells(shape, anchor), rows, cols)


@lru_cache(maxsize=8192)
def border_mask(shape: str, anchor: Cell, rows: int, cols: int) -> int:
    """The cells next to ``shape`` at ``anchor`` that lie inside the bay."""
    return mask(border(shape, anchor), rows, cols)


def expand(m: int, lay: Layout) -> int:
    """The cells next to a cell of ``m`` (inside the bay)."""
    return (((m & lay.not_last) << 1) | ((m & lay.not_first) >> 1) | (m << lay.cols) | (m >> lay.cols)) & lay.full


def flood(start: int, free: int, lay: Layout) -> list[int]:
    """Breadth-first layers from the cells of ``start`` through ``free`` cells: ``[start, cells at
    distance 1, …]`` (the loader's :func:`~.grid.reachable`, as masks)."""
    layers = [start]
    seen = frontier = start
    while True:
        frontier = expand(frontier, lay) & free & ~seen
        if not frontier:
            return layers
        seen |= frontier
        layers.append(frontier)


def cells_of(m: int, cols: int) -> Iterator[Cell]:
    """The cells of ``m`` in sorted (row-major) order."""
    while m:
        low = m & -m
        i = low.bit_length() - 1
        yield divmod(i, cols)
        m ^= low


def nearest(m: int, layers: list[int], cols: int) -> Cell | None:
    """The cell of ``m`` nearest the flood's start, the least such cell on a tie (``min`` by
    (distance, cell) over the reachable cells of ``m``); None if none is reachable."""
    for layer in layers:
        hit = layer & m
        if hit:
            return divmod((hit & -hit).bit_length() - 1, cols)
    return None
