"""Shuffled pieces (seed 003): the board, the core model, the seed's means-ends planner, our regression planner."""

from __future__ import annotations

import pytest
from helpers import replay

from nowplan.acting.monitor_support import simulate
from nowplan.domains.pieces.board import Board, Geometry, cell_rc, distance, hamming
from nowplan.domains.pieces.compare import means_ends_run, regression_run
from nowplan.domains.pieces.meansends import plan_means_ends
from nowplan.domains.pieces.model import DOMAIN, goal_reached, problem
from nowplan.domains.pieces.scenarios import Size, generate
from nowplan.domains.pieces.support import model_distance, start_arm_from_here
from nowplan.errors import ModelError, ScenarioError
from nowplan.planning.plan import PlanStatus

G4 = Geometry(4, 4)


def _plan(board: Board, goal: dict[str, str]):
    p = problem(board, goal)
    return p, plan_means_ends(DOMAIN, p.objects, p.init, p.goal)


def test_board_round_trips_through_the_core_state() -> None:
    t = generate(Size(6, 6, 6), 1)
    assert Board.from_state(t.geometry, t.init.to_state()) == t.init
    moved = t.init.move(t.init.pieces[0][0], t.init.empty_cells()[0])
    assert hamming(t.init, moved) == 2
    assert model_distance(t.init.to_state(), moved.to_state()) == 2
    assert model_distance(t.init.to_state(), t.init.with_arm("r0c0").to_state()) == 0  # the arm is no part


def test_bad_boards_are_model_errors() -> None:
    with pytest.raises(ModelError, match="outside"):
        Board.of(G4, {"r7c7": "pawn"}, "r0c0")
    with pytest.raises(ModelError, match="unknown piece kind"):
        Board.of(G4, {"r0c1": "dragon"}, "r0c0")
    with pytest.raises(ModelError, match="not a cell name"):
        cell_rc("c1r2")
    with pytest.raises(ScenarioError, match="do not fit"):
        generate(Size(2, 2, 4), 0)


@pytest.mark.parametrize("seed", range(6))
def test_means_ends_plans_replay_to_the_goal(seed: int) -> None:
    t = generate(Size(8, 8, 12), seed)
    p = t.core()
    res = plan_means_ends(DOMAIN, p.objects, p.init, p.goal)
    assert res.solved and res.plan is not None
    end = replay(DOMAIN, p.init, res.plan)  # preconditions, every pre-image and the goal
    assert goal_reached(Board.from_state(t.geometry, end), t.goal)
    assert {a.name for a in res.plan.actions} <= {"move_arm", "move_piece"}


@pytest.mark.parametrize("seed", range(6))
def test_the_arm_goes_first_to_the_closest_misplaced_piece(seed: int) -> None:
    t = generate(Size(8, 8, 12), seed)
    misplaced = [c for c, k in t.init if t.goal.get(c) != k]
    nearest = min(distance(t.init.arm, c) for c in misplaced)
    _, res = _plan(t.init, t.goal)
    first = res.plan.actions[0]
    if first.name == "move_piece":  # the arm already stood on a misplaced piece
        assert first.args[1] == t.init.arm and nearest == 0
    else:
        assert distance(t.init.arm, first.args[1]) == pytest.approx(nearest)


def test_a_piece_goes_to_the_closest_free_goal_cell_of_its_kind() -> None:
    board = Board.of(G4, {"r0c0": "pawn", "r3c0": "pawn"}, "r0c0")
    goal = {"r0c3": "pawn", "r3c3": "pawn"}  # from r0c0: r0c3 is nearer than r3c3
    _, res = _plan(board, goal)
    moves = [a for a in res.plan.actions if a.name == "move_piece"]
    assert moves[0].args[1:] == ("r0c0", "r0c3")
    assert moves[1].args[1:] == ("r3c0", "r3c3")


def test_an_occupied_destination_is_first_emptied_to_the_closest_empty_cell() -> None:
    board = Board.of(G4, {"r0c0": "pawn", "r0c1": "rook"}, "r0c0")  # the rook has no goal cell
    goal = {"r0c1": "pawn"}
    _, res = _plan(board, goal)
    names = [(a.name, a.args) for a in res.plan.actions]
    evict = next(a for a in res.plan.actions if a.name == "move_piece")
    assert evict.args[:2] == ("rook", "r0c1")
    free = [c for c in G4.board_cells if board.at(c) is None and c not in goal]
    assert distance("r0c1", evict.args[2]) == pytest.approx(min(distance("r0c1", c) for c in free))
    assert names[-1] == ("move_piece", ("pawn", "r0c0", "r0c1"))


def test_pieces_in_the_tray_are_fetched_and_missing_ones_reported() -> None:
    tray = G4.tray_cells[2]
    _, res = _plan(Board.of(G4, {tray: "queen"}, "r0c0"), {"r1c1": "queen"})
    assert res.solved and res.plan.actions[-1].args == ("queen", tray, "r1c1")
    _, res = _plan(Board.of(G4, {"r0c0": "king"}, "r0c0"), {"r1c1": "king", "r2c2": "king"})
    assert res.status is PlanStatus.UNSOLVABLE and "not enough pieces of kind king" in res.reason


@pytest.mark.parametrize("seed", range(3))
def test_regression_and_means_ends_solve_the_same_problems(seed: int) -> None:
    t = generate(Size(4, 4, 3), seed)
    ours = regression_run(t, hierarchical=False, time_limit=30.0)
    theirs = means_ends_run(t)
    assert ours.solved and theirs.solved, ours.reason
    assert ours.piece_moves >= 1 and theirs.piece_moves >= 1
    assert ours.cost > 0 and theirs.cost > 0  # both are arm travel of complete plans


def test_hpn_runs_the_pieces_model_hierarchically() -> None:
    run = regression_run(generate(Size(4, 4, 3), 0), hierarchical=True, time_limit=30.0)
    assert run.solved, run.reason


def test_arm_rerouting_keeps_plans_valid() -> None:
    t = generate(Size(6, 6, 6), 2)
    p, res = _plan(t.init, t.goal)
    elsewhere = t.init.with_arm("r5c5").to_state()
    rerouted = start_arm_from_here(list(res.plan.actions), elsewhere)
    states = simulate(DOMAIN, elsewhere, rerouted)
    assert states is not None and DOMAIN.satisfies(states[-1], p.goal)
    assert [a for a in rerouted if a.name == "move_piece"] == [
        a for a in res.plan.actions if a.name == "move_piece"]
