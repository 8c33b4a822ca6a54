"""The seed's means-ends planner for shuffled pieces, with its control rule (seed 003 Table 1).

Preconditions B / actions B: the arm goes to the misplaced piece closest to
it.  Preconditions A / actions A: that piece goes to the closest free goal
cell of its kind; an occupied destination is first emptied by carrying its
occupant to the closest empty cell.  Our one refinement of "closest empty
cell": a cell the occupant itself belongs on is taken first, then a cell no
target asks for, and only then a goal cell of another kind (which would have
to be emptied again).

Targets come from core-model goals: ``has(c, k)`` (a cell must hold ``k``),
``empty(c)`` (must be empty), ``has(c, k) = False`` (must not hold ``k``)
and ``arm_at(c)`` (the arm must end there).  The result is a
:class:`~nowplan.planning.plan.PlanResult` whose plan carries regression
pre-images, so it is interchangeable with the regression planner's.

Termination: every iteration either fills a target cell with its kind for
good, or takes a piece off a cell where it must not stand and leaves it on a
cell no target mentions; ``(unfilled target cells, misplaced pieces on
forbidden cells)`` decreases lexicographically, and a step bound guards it.
"""

from __future__ import annotations

import logging
import random
import time
from collections.abc import Mapping
from dataclasses import dataclass

from nowplan.acting.monitor_support import plan_from_actions
from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.domains.pieces.board import Board, Geometry, cell_rc, distance
from nowplan.domains.pieces.model import DOMAIN
from nowplan.errors import ModelError
from nowplan.planning.plan import PlanResult, PlanStatus

log = logging.getLogger(__name__)

MOVE_ARM = DOMAIN.operator_map["move_arm"]
MOVE_PIECE = DOMAIN.operator_map["move_piece"]


def arm_move(src: str, dst: str) -> Action:
    return MOVE_ARM.instantiate(dict(zip(MOVE_ARM.params, (src, dst), strict=True)))


def piece_move(kind: str, src: str, dst: str) -> Action:
    return MOVE_PIECE.instantiate(dict(zip(MOVE_PIECE.params, (kind, src, dst), strict=True)))


@dataclass(frozen=True)
class Target:
    """What a goal asks of cells and of the arm."""

    fill: Mapping[str, str]  # cell -> kind it must hold
    vacate: frozenset[str]  # cells that must be empty
    forbid: frozenset[tuple[str, str]]  # (cell, kind) that must not be there
    arm: str | None = None

    @staticmethod
    def of(goal: Goal) -> Target:
        fill: dict[str, str] = {}
        vacate: set[str] = set()
        forbid: set[tuple[str, str]] = set()
        arm = None
        for a in goal.atoms:
            if a.predicate == "has" and a.value is True:
                fill[str(a.args[0])] = str(a.args[1])
            elif a.predicate == "has":
                forbid.add((str(a.args[0]), str(a.args[1])))
            elif a.predicate == "empty" and a.value is True:
                vacate.add(str(a.args[0]))
            elif a.predicate == "arm_at" and a.value is True:
                arm = str(a.args[0])
        return Target(fill, frozenset(vacate), frozenset(forbid), arm)

    def mentions(self, cell: str) -> bool:
        return cell in self.fill or cell in self.vacate


class _Planner:
    def __init__(self, board: Board, target: Target, cells: list[str]) -> None:
        self.board = board
        self.target = target
        self.cells = cells  # cells the planner may use (its objects)
        self.actions: list[Action] = []

    # -- the control rule's tests ------------------------------------------------
    def forbidden(self, cell: str, kind: str) -> bool:
        t = self.target
        want = t.fill.get(cell)
        return cell in t.vacate or (want is not None and want != kind) or (cell, kind) in t.forbid

    def free_goal_cells(self, kind: str) -> list[str]:
        return [c for c, k in self.target.fill.items() if k == kind and self.board.at(c) != kind]

    def misplaced(self) -> list[str]:
        out = []
        needed = {k for k in self.target.fill.values() if self.free_goal_cells(k)}
        for cell, kind in self.board:
            if cell not in self.cells:
                continue
            if self.forbidden(cell, kind) or (kind in needed and self.target.fill.get(cell) != kind):
                out.append(cell)
        return out

    def closest(self, origin: str, cands: list[str]) -> str | None:
        return min(cands, key=lambda c: (distance(origin, c), cell_rc(c))) if cands else None

    def parking(self, near: str, kind: str, exclude: str) -> str | None:
        """Closest empty cell for a piece of ``kind``: its goal cell, else an unmentioned cell."""
        empty = [c for c in self.cells if self.board.at(c) is None and c != exclude]
        own = [c for c in empty if self.target.fill.get(c) == kind]
        free = [c for c in empty if not self.target.mentions(c) and (c, kind) not in self.target.forbid]
        other = [c for c in empty if c in self.target.fill and (c, kind) not in self.target.forbid]
        for group in (own, free, other):
            best = self.closest(near, group)
            if best is not None:
                return best
        return None

    # -- actions ---------------------------------------------------------------------
    def go(self, cell: str) -> None:
        if self.board.arm != cell:
            self.actions.append(arm_move(self.board.arm, cell))
            self.board = self.board.with_arm(cell)

    def carry(self, src: str, dst: str) -> None:
        kind = self.board.at(src)
        assert kind is not None
        self.go(src)
        self.actions.append(piece_move(kind, src, dst))
        self.board = self.board.move(src, dst)

    # -- the rule --------------------------------------------------------------------
    def run(self, max_iterations: int) -> str:
        for _ in range(max_iterations):
            todo = self.misplaced()
            if not todo:
                if self.target.arm is not None:
                    self.go(self.target.arm)
                unfilled = [c for c, k in self.target.fill.items() if self.board.at(c) != k]
                if unfilled:
                    kinds = sorted({self.target.fill[c] for c in unfilled})
                    return f"not enough pieces of kind {', '.join(kinds)} for cells {', '.join(sorted(unfilled))}"
                return ""
            # preconditions B: the arm chooses the misplaced piece closest to it
            piece = self.closest(self.board.arm, todo)
            assert piece is not None
            kind = self.board.at(piece)
            assert kind is not None
            self.go(piece)
            # preconditions A: the piece's closest free goal cell of its kind (or parking)
            dest = self.closest(piece, [c for c in self.free_goal_cells(kind) if c != piece])
            if dest is None:
                dest = self.parking(piece, kind, exclude=piece)
                if dest is None:
                    return f"no empty cell to put the {kind} from {piece}"
            occupant = self.board.at(dest)
            if occupant is not None:
                spot = self.parking(dest, occupant, exclude=dest)
                if spot is None:
                    return f"no empty cell to clear {dest} into"
                self.carry(dest, spot)
            self.carry(piece, dest)
        return f"no plan within {max_iterations} control-rule iterations"


def plan_means_ends(
    domain: Domain,
    objects: Mapping[str, str | None],
    state: State,
    goal: Goal,
    rng: random.Random | None = None,
    geometry: Geometry | None = None,
) -> PlanResult:
    """Plan with the seed's control rule from ``state`` to ``goal`` (a core-model goal).

    ``objects`` limits the cells used; ``rng`` is unused (the rule is
    deterministic: ties go to the lower row, then column) and only keeps
    the signature of the monitor's planners.
    """
    t_cpu = time.process_time()
    geometry = geometry or geometry_of(state)
    board = Board.from_state(geometry, state)
    cells = [c for c in geometry.cells if c in objects]
    planner = _Planner(board, Target.of(goal), cells)
    bound = 4 * (len(cells) + len(goal) + 1)
    reason = planner.run(bound)
    cpu = time.process_time() - t_cpu
    if reason:
        log.info("means-ends planner failed: %s", reason)
        return PlanResult(PlanStatus.UNSOLVABLE, None, reason, cpu_time_s=cpu, method="means-ends")
    plan = plan_from_actions(domain, planner.actions, goal)
    cpu = time.process_time() - t_cpu
    if plan is None:  # cannot happen for a consistent model; reported rather than raised
        return PlanResult(PlanStatus.UNSOLVABLE, None, "plan does not regress", cpu_time_s=cpu,
                          method="means-ends")
    return PlanResult(PlanStatus.SOLVED, plan, "", expanded=len(planner.actions), cpu_time_s=cpu,
                      method="means-ends")


def geometry_of(state: State) -> Geometry:
    """The board geometry from a full pieces state: the tray is the last column, one apart."""
    rcs = [cell_rc(str(args[0])) for p in ("has", "empty") for args in state.facts(p)]
    if not rcs:
        raise ModelError("a pieces state lists no cells (has/empty facts)")
    rows = max(r for r, _ in rcs) + 1
    tray = max(c for _, c in rcs)
    return Geometry(rows, tray - 1)
