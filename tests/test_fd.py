"""The Fast Downward engine, plans rebuilt by regression, and UPF validation."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.core.atoms import atom
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.errors import ModelError
from nowplan.io.pddl_read import load_pddl

from test_pddl_read import DATA
from test_pddl_write import CASES

pytest.importorskip("unified_planning")
pytest.importorskip("up_fast_downward")

from nowplan.planning.fd import ground_actions, plan_from_actions, solve_fd  # noqa: E402
from nowplan.planning.validate import validate_plan  # noqa: E402


def replay(problem, plan) -> None:  # type: ignore[no-untyped-def]
    """Every pre-image holds when it should, along the concrete execution."""
    state = problem.init
    assert problem.domain.satisfies(state, plan.preimage(0))
    for i, a in enumerate(plan.actions, start=1):
        assert all(problem.domain.holds(p, state) for p in a.preconditions()), a
        state = state.apply(a.effects())
        assert problem.domain.satisfies(state, plan.preimage(i)), (i, a)
    assert problem.domain.satisfies(state, problem.goal)


@pytest.mark.parametrize(("domain", "problem"), CASES)
def test_fd_solves_and_validates(domain: str, problem: str) -> None:
    dpath, ppath = DATA / domain / "domain.pddl", DATA / domain / problem
    prob = load_pddl(dpath, ppath)
    result = solve_fd(prob, time_limit=30)
    assert result.solved and result.plan is not None, result.reason
    assert result.method == "fast-downward"
    replay(prob, result.plan)
    ok, msg = validate_plan(dpath, ppath, [a.pddl() for a in result.plan.actions])
    assert ok, msg


def test_fd_at_the_top_level_of_logistics() -> None:
    log = DATA / "logistics"
    prob = load_pddl(log / "domain.pddl", log / "p03.pddl", log / "logistics.crit")
    result = solve_fd(prob, prob.domain.top_level, time_limit=30)
    assert result.solved and result.plan is not None
    names = {a.name for a in result.plan.actions}
    assert names <= {"load-truck", "unload-truck", "load-airplane", "unload-airplane"}
    assert not any(result.plan.is_primitive(i) for i in range(1, len(result.plan) + 1))
    # pre-images mention packages only (vehicle positions are hidden at the top level)
    for step in result.plan.steps:
        assert all(a.args[0].startswith("pkg") for a in step.goal.atoms)


def test_fd_reports_unsolvable(tmp_path: Path) -> None:
    bw = DATA / "blocksworld"
    text = (bw / "p01.pddl").read_text().replace("(on a b) (on b c)", "(on a b) (on b a)")
    (tmp_path / "p.pddl").write_text(text)
    prob = load_pddl(bw / "domain.pddl", tmp_path / "p.pddl")
    result = solve_fd(prob, time_limit=30)
    assert not result.solved and result.plan is None
    assert result.status.value == "unsolvable"


def test_fd_counts_the_readers_time_against_the_limit() -> None:
    """A limit smaller than unified-planning's reading time ends the call as a time limit, not a hang."""
    log = DATA / "logistics"
    prob = load_pddl(log / "domain.pddl", log / "p03.pddl")
    result = solve_fd(prob, time_limit=1e-6)
    assert result.status.value == "time_limit" and "read the problem" in result.reason


def test_plan_from_actions_rejects_non_plans() -> None:
    bw = DATA / "blocksworld"
    prob = load_pddl(bw / "domain.pddl", bw / "p01.pddl")
    good = ground_actions(prob, [("unstack", ["c", "a"]), ("put-down", ["c"]), ("pick-up", ["b"]),
                                 ("stack", ["b", "c"]), ("pick-up", ["a"]), ("stack", ["a", "b"])])
    p = plan_from_actions(prob, good, flat_levels())
    assert len(p) == 6 and p.goal == prob.goal
    assert atom("handempty") in p.preimage(0).atoms
    with pytest.raises(ModelError, match="initial state does not satisfy"):
        plan_from_actions(prob, good[2:], flat_levels())
    with pytest.raises(ModelError, match="unknown action 'fly'"):
        ground_actions(prob, [("fly", ["a"])])
    with pytest.raises(ModelError, match="unknown object 'z'"):
        ground_actions(prob, [("pick-up", ["z"])])
    with pytest.raises(ModelError, match="takes 1 argument"):
        ground_actions(prob, [("pick-up", ["a", "b"])])
    # at a level that hides nothing the plan is the same
    assert plan_from_actions(prob, good, LevelMap(0)).steps == p.steps


def test_validator_rejects_bad_plans() -> None:
    bw = DATA / "blocksworld"
    ok, msg = validate_plan(bw / "domain.pddl", bw / "p01.pddl", ["(unstack c a)", "(pick-up b)"])
    assert not ok and "pick-up" in msg
    ok, msg = validate_plan(bw / "domain.pddl", bw / "p01.pddl", ["(unstack c a)"])
    assert not ok and "UNSATISFIED_GOALS" in msg
    ok, msg = validate_plan(bw / "domain.pddl", bw / "p01.pddl", ["(fly c a)"])
    assert not ok and "does not parse" in msg
