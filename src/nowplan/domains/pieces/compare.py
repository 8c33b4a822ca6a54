"""The seed's means-ends planner and our regression planner on the same shuffled-pieces problems.

Both produce plans of the same primitives whose cost is the arm's travel, so
their plans compare directly.  The regression planner runs through the HPN
executive (hierarchically: piece moves first, arm moves when a piece move is
refined) in a noise-free symbolic world, or flat with a single call; it is
given the cells that matter (pieces, goal cells, the arm and a few empty
cells next to the goal cells) because grounding every cell of an 8×8 board
makes its search too slow (see docs/pieces.md).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, replace

from nowplan.acting.hpn import Executive
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.domain import Problem
from nowplan.core.levels import flat_levels
from nowplan.domains.pieces.board import Board, distance
from nowplan.domains.pieces.meansends import plan_means_ends
from nowplan.domains.pieces.model import DOMAIN
from nowplan.domains.pieces.scenarios import PiecesProblem
from nowplan.planning.regression import PlannerConfig
from nowplan.planning.regression import plan as regression_plan
from nowplan.worlds.symbolic import SymbolicWorld


@dataclass(frozen=True)
class PlannerRun:
    planner: str
    solved: bool
    cost: float  # arm travel of the plan (or of the executed run, for HPN)
    piece_moves: int
    cpu_s: float
    reason: str = ""


def relevant_objects(board: Board, goal: dict[str, str], spare: int = 4) -> dict[str, str | None]:
    """Cells with pieces, goal cells, the arm's cell and the ``spare`` empty cells nearest the goal cells."""
    cells = {c for c, _ in board} | set(goal) | {board.arm}
    empty = [c for c in board.geometry.board_cells if c not in cells]
    empty.sort(key=lambda e: (min(distance(e, gc) for gc in goal) if goal else 0.0, e))
    cells |= set(empty[:spare])
    return {c: "cell" for c in sorted(cells)}


def means_ends_run(task: PiecesProblem) -> PlannerRun:
    p = task.core()
    res = plan_means_ends(DOMAIN, p.objects, p.init, p.goal)
    if not res.solved or res.plan is None:
        return PlannerRun("means-ends", False, 0.0, 0, res.cpu_time_s, res.reason)
    moves = sum(1 for a in res.plan.actions if a.name == "move_piece")
    return PlannerRun("means-ends", True, res.plan.cost(), moves, res.cpu_time_s)


def regression_run(task: PiecesProblem, hierarchical: bool = True, time_limit: float = 60.0,
                   spare: int = 4, seed: int = 0) -> PlannerRun:
    """Our regression planner: HPN through the executive, or one flat call."""
    objects = relevant_objects(task.init, task.goal, spare)
    core = task.core()
    prob = Problem(DOMAIN, objects, core.init, core.goal, core.name)
    name = "regression (hpn)" if hierarchical else "regression (flat)"
    if not hierarchical:
        res = regression_plan(DOMAIN, objects, prob.init, prob.goal, flat_levels(),
                              PlannerConfig(time_limit=time_limit, seed=seed))
        if not res.solved or res.plan is None:
            return PlannerRun(name, False, 0.0, 0, res.cpu_time_s, res.reason)
        moves = sum(1 for a in res.plan.actions if a.name == "move_piece")
        return PlannerRun(name, True, res.plan.cost(), moves, res.cpu_time_s)
    world = SymbolicWorld(DOMAIN, prob.init, seed=seed)
    strategy = replace(parse_strategy("hpn", time_limit=time_limit),
                       planner=PlannerConfig(time_limit=time_limit, seed=seed))
    t0 = time.perf_counter()
    m = Executive(prob, world, SymbolicBelief(prob.init), strategy, seed=seed).run()
    ok = m.outcome.value == "reached" and DOMAIN.satisfies(world.state, prob.goal)
    reason = "" if ok else (m.reason or f"stopped after {time.perf_counter() - t0:.1f} s")
    return PlannerRun(name, ok, m.execution_cost, m.action_counts.get("move_piece", 0),
                      m.planning_cpu_s, reason)
