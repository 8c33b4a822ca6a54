from __future__ import annotations

import gc
import json

import pytest

from nowplan.acting.hpn import Executive
from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.logistics import episode
from nowplan.errors import ScenarioError
from nowplan.trace import Trace


def _world_goal_holds(ep):
    return ep.problem.domain.satisfies(ep.world.state, ep.problem.goal)


@pytest.mark.parametrize("strategy", ["hpn", "flat", "hpn+aggressive"])
def test_logistics_reaches_goal(strategy):
    ep = episode("small", 1)
    m = run_episode(ep, parse_strategy(strategy), seed=1)
    assert m.outcome is Outcome.REACHED, m.reason
    assert _world_goal_holds(ep)
    assert m.actions == sum(m.action_counts.values()) == m.execution_cost  # unit costs
    assert m.plans_made >= 1


@pytest.mark.parametrize("seed", range(3))
def test_hpn_recovers_from_injected_failures(seed):
    ep = episode("small", seed, failure_prob=0.25)
    tr = Trace()
    m = run_episode(ep, parse_strategy("hpn"), seed=seed, trace=tr)
    assert m.outcome is Outcome.REACHED, m.reason
    assert _world_goal_holds(ep)
    assert ep.world.failures > 0
    assert len(tr.of("failure")) >= ep.world.failures
    assert m.replans >= 1 and len(tr.of("replan")) == m.replans
    assert all(r["trigger"] == "failure" for r in tr.of("replan"))


def test_hpn_handles_exogenous_changes():
    ep = episode("small", 4, exogenous_prob=0.2)
    m = run_episode(ep, parse_strategy("hpn"), seed=4)
    assert m.outcome is Outcome.REACHED
    assert ep.world.exogenous_events > 0 and _world_goal_holds(ep)


def test_hierarchy_plans_more_but_smaller_problems_than_flat():
    hpn = run_episode(episode("medium", 0), parse_strategy("hpn"), seed=0)
    flat = run_episode(episode("medium", 0), parse_strategy("flat"), seed=0)
    assert hpn.outcome is flat.outcome is Outcome.REACHED
    assert flat.plans_made == 1 and hpn.plans_made > 5


def test_budget_stops_with_a_reason():
    ep = episode("small", 0, failure_prob=0.5)
    m = run_episode(ep, parse_strategy("hpn", max_actions=4), seed=0)
    assert m.outcome is Outcome.LIMIT and "action budget of 4" in m.reason
    assert m.actions == 4


def test_belief_is_separate_from_world_state():
    ep = episode("tiny", 0)
    assert ep.belief.state is ep.world.state  # same value at the start is fine...
    ep.world.state = ep.world.state.apply([])  # ...but the world moves its own copy
    assert ep.belief.state is not ep.world.state


def test_trace_records_the_run(tmp_path):
    path = tmp_path / "t.jsonl"
    with Trace(path) as tr:
        m = run_episode(episode("tiny", 0, failure_prob=0.3), parse_strategy("hpn"), seed=0, trace=tr)
    lines = [json.loads(x) for x in path.read_text().splitlines()]
    assert [e["seq"] for e in lines] == list(range(len(lines)))
    assert lines[0]["event"] == "run_start" and lines[-1]["event"] == "run_end"
    assert lines[-1]["metrics"] == m.to_dict()
    plans = [e for e in lines if e["event"] == "plan"]
    assert len(plans) == m.plans_made
    for p in plans:
        assert p["steps"][0]["action"] is None and set(p["steps"][-1]["preimage"]) == set(p["goal"])
    assert sum(1 for e in lines if e["event"] == "action") == m.actions


def test_same_seed_same_run():
    a = run_episode(episode("small", 3, failure_prob=0.2), parse_strategy("hpn"), seed=3).to_dict()
    b = run_episode(episode("small", 3, failure_prob=0.2), parse_strategy("hpn"), seed=3).to_dict()
    for k in ("planning_cpu_s", "wall_s"):
        a.pop(k), b.pop(k)
    assert a == b


def test_unknown_and_planned_strategies_are_refused():
    with pytest.raises(ScenarioError, match="valid strategies: aggressive, deferred, domain-planner, flat, flexible, foresight, h2, hpn, maintain, monitor"):
        parse_strategy("hpn+bogus")
    # seed 004's switches select the online policy; the plan-stack executive refuses them
    from nowplan.acting.hpn import Executive

    ep = episode("tiny", 0)
    ex = Executive(ep.problem, ep.world, ep.belief, parse_strategy("hpn+reuse"))
    with pytest.raises(ScenarioError, match="online replanning policy"):
        ex.run()


def test_exogenous_changes_move_only_packages():
    for seed in range(5):
        ep = episode("small", seed, exogenous_prob=1.0)
        vehicles = {o for o, t in ep.problem.objects.items() if t in ("truck", "airplane")}
        before = {a for a in ep.world.state.atoms() if a.args and a.args[0] in vehicles}
        for _ in range(10):
            ep.world.exogenous(ep.world.state, ep.world.rng)
            ep.world.state = ep.world.state.apply(ep.world.exogenous(ep.world.state, ep.world.rng))
        after = {a for a in ep.world.state.atoms() if a.args and a.args[0] in vehicles}
        assert before == after


def test_run_freezes_the_heap_it_starts_with_and_unfreezes_it_after(monkeypatch):
    """The objects alive when the run starts are out of the collector's generations during the run
    (acting/run.py), and back after it, also when the run raises."""
    seen: list[int] = []
    run = Executive.run

    def spy(self):
        seen.append(gc.get_freeze_count())
        return run(self)

    monkeypatch.setattr(Executive, "run", spy)
    assert gc.get_freeze_count() == 0
    m = run_episode(episode("small", 1), parse_strategy("hpn"), seed=1)
    assert m.outcome is Outcome.REACHED, m.reason
    assert seen and seen[0] > 0
    assert gc.get_freeze_count() == 0

    def boom(self):
        raise RuntimeError("boom")

    monkeypatch.setattr(Executive, "run", boom)
    with pytest.raises(RuntimeError):
        run_episode(episode("small", 1), parse_strategy("hpn"), seed=1)
    assert gc.get_freeze_count() == 0


def test_run_leaves_a_callers_freeze_as_it_is():
    gc.freeze()
    try:
        m = run_episode(episode("small", 1), parse_strategy("hpn"), seed=1)
        assert m.outcome is Outcome.REACHED, m.reason
        assert gc.get_freeze_count() > 0  # not unfrozen (frozen objects freed meanwhile leave the count)
    finally:
        gc.unfreeze()
