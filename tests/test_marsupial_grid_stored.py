"""grid.stored (memoised) agrees with its definition: every cell of the shape in storage."""

from __future__ import annotations

from nowplan.domains.marsupial.grid import SHAPES, SIZES, Hold, cells, in_storage, stored


def test_stored_matches_the_cells_definition_everywhere():
    for rows, cols in SIZES:
        for shape in SHAPES:
            for r in range(-1, rows + 1):
                for c in range(-1, cols + 1):
                    want = all(in_storage(x, rows, cols) for x in cells(shape, (r, c)))
                    assert stored(shape, (r, c), rows, cols) is want


def test_hold_stored_is_false_once_one_package_reaches_the_load_region():
    inside = Hold(3, 6, (("a", "dot", (0, 0)), ("b", "bar", (2, 2))), (1, 1))
    assert inside.stored()
    out = Hold(3, 6, (("a", "dot", (0, 0)), ("b", "bar", (2, 3))), (1, 1))  # b covers column 4
    assert not out.stored()
