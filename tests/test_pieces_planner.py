"""The pieces domain's own planner behind the executive's ``domain-planner`` switch, and seed 000's
flexible execution with serendipity running on it through the camera loop with disturbances."""

from __future__ import annotations

import pytest

from nowplan.acting.hpn import Executive
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.domains.pieces.board import Board, Geometry
from nowplan.domains.pieces.meansends import plan_means_ends
from nowplan.domains.pieces.model import DOMAIN, goal_reached, problem
from nowplan.domains.pieces.planner import abstract_level, means_ends_for_executive
from nowplan.domains.pieces.scenarios import Size, generate, make_episode
from nowplan.worlds.symbolic import SymbolicWorld

G4 = Geometry(4, 4)
START = Board.of(G4, {"r0c0": "pawn", "r0c1": "rook", "r0c2": "king"}, "r3c3")
GOAL = {"r3c0": "pawn", "r3c1": "rook", "r3c2": "king"}
BUDGET = 200


def test_the_domain_brings_the_means_ends_planner() -> None:
    p = problem(START, GOAL)
    res = DOMAIN.planner(DOMAIN, p.objects, SymbolicBelief(p.init), p.goal, flat_levels(), None, None, None)
    direct = plan_means_ends(DOMAIN, p.objects, p.init, p.goal)
    assert res.solved and res.plan is not None and direct.plan is not None
    assert res.plan.actions == direct.plan.actions  # flat: the concrete plan, arm moves included
    assert all(res.plan.is_primitive(i) for i in range(1, len(res.plan) + 1))


def test_at_hpn_s_top_level_the_plan_is_its_piece_moves() -> None:
    p = problem(START, GOAL)
    top = LevelMap(DOMAIN.top_level)
    assert abstract_level(top, DOMAIN) and not abstract_level(flat_levels(), DOMAIN)
    res = means_ends_for_executive(DOMAIN, p.objects, SymbolicBelief(p.init), p.goal, top)
    assert res.solved and res.plan is not None
    assert [a.name for a in res.plan.actions] == ["move_piece"] * 3
    assert not any(res.plan.is_primitive(i) for i in range(1, 4))  # each is refined by the executive
    assert all(x.predicate != "arm_at" for i in range(4) for x in res.plan.preimage(i).atoms)
    # a refined step (the level map has an override) gets the concrete plan
    first = res.plan.actions[0]
    refined = means_ends_for_executive(DOMAIN, p.objects, SymbolicBelief(p.init), res.plan.preimage(1),
                                       top.next_level(first))
    assert refined.plan is not None and [a.name for a in refined.plan.actions] == ["move_arm", "move_piece"]


@pytest.mark.parametrize("mode", ["hpn", "flat"])
def test_flexible_serendipity_on_the_domain_planner_without_disturbances(mode: str) -> None:
    p = problem(START, GOAL)
    world = SymbolicWorld(DOMAIN, p.init)
    strategy = parse_strategy(f"{mode}+flexible+serendipity+domain-planner", max_actions=BUDGET)
    m = Executive(p, world, SymbolicBelief(p.init), strategy, seed=0).run()
    assert m.outcome.value == "reached", m.reason
    assert DOMAIN.satisfies(world.state, p.goal)
    assert m.action_counts["move_piece"] == 3  # no wasted piece move


@pytest.mark.parametrize("mode", ["hpn", "flat"])
@pytest.mark.parametrize("seed", [0, 1])
def test_flexible_serendipity_reaches_the_goal_through_camera_and_disturbances(mode: str, seed: int) -> None:
    pytest.importorskip("sklearn")
    pytest.importorskip("PIL")
    from nowplan.domains.pieces.vision import recognizer

    task = generate(Size(6, 6, 6), 20 + seed)
    ep = make_episode(task, seed, 0.3, rec=recognizer(0))
    strategy = parse_strategy(f"{mode}+flexible+serendipity+domain-planner", max_actions=BUDGET)
    ex = Executive(ep.problem, ep.world, ep.belief, strategy, seed=seed)
    m = ex.run()
    assert ep.world.exogenous_events > 0  # the person did interfere
    assert m.outcome.value == "reached", m.reason
    assert goal_reached(ep.world.board, task.goal)  # in the true world, not only in the belief
    assert m.actions < BUDGET and m.replans > 0
