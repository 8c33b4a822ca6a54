"""Board geometry and placements for the shuffled-pieces domain (seed 003).

A board has ``rows × cols`` cells named ``r{row}c{col}``.  Beside it, one
empty column away, is a *tray* column (cells ``r{i}c{cols+1}``): a person
who "removes" a piece puts it there, so a removal never makes the task
impossible, only more expensive.  A :class:`Board` is a placement (which
kind of piece stands on which cell) and the arm's cell; pieces of one kind
are interchangeable, as in the seed (cells carry labels, not identities).
Distances are straight-line (Euclidean) in cell units: the arm's travel.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from functools import lru_cache

from nowplan.core.atoms import Atom, atom
from nowplan.core.state import State
from nowplan.errors import ModelError

# the seed's six kinds (Turkish letters in the seed: P(iyon), A(t), F(il), K(ale), V(ezir), S(ah))
KINDS = ("pawn", "knight", "bishop", "rook", "queen", "king")
LETTERS = {"pawn": "P", "knight": "N", "bishop": "B", "rook": "R", "queen": "Q", "king": "K"}
EMPTY = "empty"
LABELS = (EMPTY, *KINDS)  # classifier classes, index 0 = empty cell


def cell_name(r: int, c: int) -> str:
    return f"r{r}c{c}"


@lru_cache(maxsize=4096)
def cell_rc(name: str) -> tuple[int, int]:
    """``"r3c4"`` -> ``(3, 4)``; raises :class:`ModelError` for anything else."""
    try:
        r_part, c_part = name[1:].split("c")
        if not name.startswith("r"):
            raise ValueError(name)
        return int(r_part), int(c_part)
    except ValueError:
        raise ModelError(f"'{name}' is not a cell name (expected r<row>c<col>, e.g. r0c3)") from None


@lru_cache(maxsize=65536)
def distance(a: str, b: str) -> float:
    """Straight-line distance between two cells, in cell units."""
    (ra, ca), (rb, cb) = cell_rc(a), cell_rc(b)
    return math.hypot(ra - rb, ca - cb)


@dataclass(frozen=True)
class Geometry:
    rows: int = 8
    cols: int = 8

    def __post_init__(self) -> None:
        if self.rows < 2 or self.cols < 2:
            raise ModelError(f"a board needs at least 2×2 cells, got {self.rows}×{self.cols}")

    @property
    def board_cells(self) -> tuple[str, ...]:
        return tuple(cell_name(r, c) for r in range(self.rows) for c in range(self.cols))

    @property
    def tray_col(self) -> int:
        return self.cols + 1

    @property
    def tray_cells(self) -> tuple[str, ...]:
        return tuple(cell_name(r, self.tray_col) for r in range(self.rows))

    @property
    def cells(self) -> tuple[str, ...]:
        return self.board_cells + self.tray_cells

    def on_board(self, cell: str) -> bool:
        r, c = cell_rc(cell)
        return 0 <= r < self.rows and 0 <= c < self.cols

    def in_tray(self, cell: str) -> bool:
        r, c = cell_rc(cell)
        return 0 <= r < self.rows and c == self.tray_col

    def check(self, cell: str) -> None:
        if not (self.on_board(cell) or self.in_tray(cell)):
            raise ModelError(f"cell {cell} is outside a {self.rows}×{self.cols} board and its tray")


@dataclass(frozen=True)
class Board:
    """Which kind stands on which cell (board and tray), and where the arm is."""

    geometry: Geometry
    pieces: tuple[tuple[str, str], ...]  # sorted (cell, kind)
    arm: str
    _index: dict[str, str] = field(default_factory=dict, compare=False, hash=False, repr=False)

    def __post_init__(self) -> None:
        seen: dict[str, str] = {}
        for cell, kind in self.pieces:
            self.geometry.check(cell)
            if kind not in KINDS:
                raise ModelError(f"unknown piece kind '{kind}'; kinds: {', '.join(KINDS)}")
            if cell in seen:
                raise ModelError(f"two pieces on cell {cell}")
            seen[cell] = kind
        self.geometry.check(self.arm)
        self._index.update(seen)

    @staticmethod
    def of(geometry: Geometry, placement: Mapping[str, str] | Iterable[tuple[str, str]], arm: str) -> Board:
        items = placement.items() if isinstance(placement, Mapping) else placement
        return Board(geometry, tuple(sorted(items)), arm)

    # -- queries -------------------------------------------------------------
    def at(self, cell: str) -> str | None:
        return self._index.get(cell)

    def placement(self) -> dict[str, str]:
        return dict(self._index)

    def empty_cells(self, board_only: bool = True) -> list[str]:
        cells = self.geometry.board_cells if board_only else self.geometry.cells
        return [c for c in cells if c not in self._index]

    def count(self, kind: str) -> int:
        return sum(1 for _, k in self.pieces if k == kind)

    def labels(self) -> dict[str, str]:
        """Every cell's label (a kind or ``empty``), board and tray."""
        return {c: self._index.get(c, EMPTY) for c in self.geometry.cells}

    def __iter__(self) -> Iterator[tuple[str, str]]:
        return iter(self.pieces)

    # -- updates -------------------------------------------------------------
    def move(self, src: str, dst: str) -> Board:
        kind = self._index.get(src)
        if kind is None:
            raise ModelError(f"no piece on {src}")
        if dst in self._index:
            raise ModelError(f"cell {dst} is occupied")
        m = dict(self._index)
        del m[src]
        m[dst] = kind
        return Board.of(self.geometry, m, dst)

    def with_arm(self, cell: str) -> Board:
        return Board(self.geometry, self.pieces, cell)

    def with_labels(self, labels: Mapping[str, str]) -> Board:
        """A board whose placement is ``labels`` (cell -> kind or ``empty``), same arm."""
        return Board.of(self.geometry, {c: k for c, k in labels.items() if k != EMPTY}, self.arm)

    # -- the core model ------------------------------------------------------
    def to_state(self) -> State:
        facts: list[Atom] = [atom("arm_at", self.arm)]
        for c in self.geometry.cells:
            k = self._index.get(c)
            facts.append(atom("has", c, k) if k is not None else atom("empty", c))
        return State(facts)

    @staticmethod
    def from_state(geometry: Geometry, state: State) -> Board:
        placement = {str(args[0]): str(args[1]) for args in state.facts("has")}
        arms = state.facts("arm_at")
        if len(arms) != 1:
            raise ModelError(f"a pieces state needs exactly one arm_at fact, got {len(arms)}")
        return Board.of(geometry, placement, str(arms[0][0]))

    def render_text(self, goal: Mapping[str, str] | None = None) -> str:
        """Rows of letters (``.`` empty, lower case = misplaced w.r.t. ``goal``); tray after ``|``."""
        lines = []
        g = self.geometry
        for r in range(g.rows):
            row = []
            for c in range(g.cols):
                cell = cell_name(r, c)
                k = self._index.get(cell)
                ch = LETTERS[k] if k else "."
                if goal is not None and k and goal.get(cell) != k:
                    ch = ch.lower()
                row.append(ch)
            t = self._index.get(cell_name(r, g.tray_col))
            lines.append(" ".join(row) + " | " + (LETTERS[t] if t else "."))
        return "\n".join(lines)


def hamming(a: Board, b: Board) -> int:
    """Cells (board and tray) whose labels differ: the seed's model comparison."""
    cells = set(a.geometry.cells) | set(b.geometry.cells)
    return sum(1 for c in cells if a.at(c) != b.at(c))
