"""``PlannerConfig.retry_weight``: a regression call whose full search spends its nodes searches once more, greedier.

The `flat` strategy sets it (the held-out greenhouse: A* with h_add spent 50,000 nodes on the whole goal,
weight 5 plans it); a call that succeeds or is off keeps its plan and its counters.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from nowplan.acting.strategy import parse_strategy
from nowplan.core.levels import flat_levels
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan
from strips_model import applicable, step, truth

ROOT = Path(__file__).resolve().parents[1]
CASES = [ROOT / "src/nowplan/data/pddl/logistics" / "p04.pddl", ROOT / "benchmarks/classical/gripper" / "p03.pddl",
         ROOT / "benchmarks/classical/zenotravel" / "p03.pddl"]
BASE = PlannerConfig(engine="regression", serialization=False, monotonic=False, max_nodes=300, clock="cpu",
                     time_limit=600.0)


@pytest.mark.parametrize("problem", CASES, ids=lambda p: p.parent.name)
def test_a_spent_full_search_is_retried_greedier(problem: Path) -> None:
    p = load_pddl(problem.parent / "domain.pddl", problem)
    off = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), BASE)
    assert off.status is PlanStatus.NODE_LIMIT and off.attempts == ("full:node_limit",)
    on = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), replace(BASE, retry_weight=5.0))
    assert on.status is PlanStatus.SOLVED and on.method == "weighted"
    assert on.attempts == ("full:node_limit", "weighted:solved")
    assert BASE.max_nodes < on.expanded <= 2 * BASE.max_nodes + 2
    state = p.init  # the plan replays to the goal
    for act in on.plan.actions:
        assert applicable(act, state)
        state = step(state, act)
    assert all(truth(state, a) for a in p.goal.atoms)


def test_a_solved_call_is_not_retried() -> None:
    problem = CASES[0]
    p = load_pddl(problem.parent / "domain.pddl", problem)
    roomy = replace(BASE, max_nodes=50_000)
    a = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), roomy)
    b = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), replace(roomy, retry_weight=5.0))
    assert a.solved and b.solved and a.attempts == b.attempts == ("full:solved",)
    assert (a.expanded, a.plan.actions) == (b.expanded, b.plan.actions)


def test_flat_sets_it_hpn_does_not() -> None:
    assert parse_strategy("flat").planner.retry_weight == 5.0
    assert parse_strategy("hpn").planner.retry_weight == 0.0
