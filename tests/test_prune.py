"""Greedy action elimination for the regression engine's plans, checked by regression (planning/prune.py).

A courier on a line ``home - r1 - r2`` must process item ``a`` (in r2) and end at home.  The plan
``move home r1, move r1 home, move home r1, move r1 r2, process a r2, move r2 r1, move r1 home``
goes to r1 and back for nothing: pruning drops the detour's two moves (the second one left without
its precondition once the first goes) and keeps a plan whose pre-images regress exactly.
"""

from __future__ import annotations

import pytest

from nowplan.api import (
    Domain, Goal, Operator, Outcome, Precondition, Predicate, State, Var, atom, exactly_one, parse_strategy,
    run_episode, static,
)
from nowplan.core.levels import flat_levels
from nowplan.planning.preimage import preimage, static_drop
from nowplan.planning.prune import prune, without
from tests.helpers import example_spec

r, r2, x = Var("r"), Var("r2"), Var("x")
PREDS = {p.name: p for p in (Predicate("robot_at", 1), Predicate("item_in", 2), Predicate("processed", 1),
                             Predicate("link", 2))}
MOVE = Operator("move", (r, r2), (Precondition(atom("robot_at", r), 1), static(atom("link", r, r2))),
                (atom("robot_at", r2), atom("robot_at", r, value=False)))
PROCESS = Operator("process", (x, r), (static(atom("item_in", x, r)), Precondition(atom("robot_at", r), 1)),
                   (atom("processed", x),))
DOMAIN = Domain("courier", PREDS, (MOVE, PROCESS), conflicts=(exactly_one("robot_at", key=()),))
LINKS = [atom("link", a, b) for a, b in (("home", "r1"), ("r1", "r2"), ("r1", "home"), ("r2", "r1"))]
INIT = State([atom("robot_at", "home"), atom("item_in", "a", "r2"), *LINKS])
GOAL = Goal.of([atom("processed", "a"), atom("robot_at", "home")])


def move(a: str, b: str) -> object:
    return MOVE.instantiate({r: a, r2: b})


def test_a_detour_is_pruned_and_the_rest_regresses_exactly() -> None:
    plan = [move("home", "r1"), move("r1", "home"), move("home", "r1"), move("r1", "r2"),
            PROCESS.instantiate({x: "a", r: "r2"}), move("r2", "r1"), move("r1", "home")]
    levels = flat_levels()
    steps = prune(DOMAIN, INIT, GOAL, plan, levels, lambda a: 1.0)  # type: ignore[arg-type]
    assert steps is not None
    kept = [a for a, _ in steps[1:]]
    assert [str(a) for a in kept] == ["move(home, r1)", "move(r1, r2)", "process(a, r2)", "move(r2, r1)",
                                      "move(r1, home)"]
    drop = static_drop(DOMAIN, INIT)
    for i in range(1, len(steps)):
        a, g = steps[i]
        assert a is not None
        pre = preimage(g, a, levels.level(a), DOMAIN, drop)
        assert pre is not None and set(pre.atoms) == set(steps[i - 1][1].atoms)
    assert DOMAIN.satisfies(INIT, steps[0][1])


def test_a_plan_without_redundant_steps_is_kept() -> None:
    plan = [move("home", "r1"), move("r1", "r2"), PROCESS.instantiate({x: "a", r: "r2"}), move("r2", "r1"),
            move("r1", "home")]
    assert prune(DOMAIN, INIT, GOAL, plan, flat_levels(), lambda a: 1.0) is None  # type: ignore[arg-type]


def test_removing_a_step_drops_the_steps_it_leaves_without_a_precondition() -> None:
    plan = [move("home", "r1"), move("r1", "r2"), PROCESS.instantiate({x: "a", r: "r2"})]
    # without the first move the robot is still home: the second move and the processing go too, and
    # the goal's processed(a) fails, so the try is rejected before any regression
    assert without(DOMAIN, INIT, plan, flat_levels(), 0) == []  # type: ignore[arg-type]
    assert without(DOMAIN, INIT, plan, flat_levels(), 0, GOAL) is None  # type: ignore[arg-type]


def test_the_held_out_feeder_repair_loses_its_second_spare(monkeypatch: pytest.MonkeyPatch) -> None:
    """examples/gridfix, flat, seed 0: a plan bought a second spare and replaced a segment replaced
    already (benchmarks/results/heldout17/README.md, finding 4): 40 actions unpruned, 30 pruned."""
    example_spec(monkeypatch, "gridfix")
    from gridfix_domain import scenarios  # noqa: PLC0415

    pruned = run_episode(scenarios.episode(0), parse_strategy("flat", max_actions=200), seed=0)
    kept = run_episode(scenarios.episode(0), parse_strategy("flat+noprune", max_actions=200), seed=0)
    assert pruned.outcome is kept.outcome is Outcome.REACHED
    assert pruned.actions < kept.actions and pruned.execution_cost < kept.execution_cost
