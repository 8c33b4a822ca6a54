"""The monitor's escalation from restoring to replanning to the goal (seed 003's third way), the
loops cut from composed repairs, and the monitor's replanning at the strategy's levels under HPN."""

from __future__ import annotations

import random

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.acting.hpn import Executive
from nowplan.acting.monitor import Monitor, MonitorConfig, monitor_settings
from nowplan.acting.monitor_escalation import Escalation
from nowplan.acting.monitor_support import drop_loops, simulate
from nowplan.acting.progress import Cycle
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Atom, Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.state import State
from nowplan.domains.logistics.model import DOMAIN as LOGISTICS
from nowplan.domains.logistics.scenarios import SIZES, generate
from nowplan.core.levels import flat_levels
from nowplan.planning.task import grounding
from nowplan.trace import Trace
from nowplan.worlds.symbolic import SymbolicWorld

PLACES = ("c0-l0", "c0-l1", "c0-l2", "c0-l3")


def ground_actions(domain: object, objects: dict[str, str | None], init: State) -> list:  # type: ignore[type-arg]
    return list(grounding(LOGISTICS, objects, init, flat_levels().top).actions)


def one_city(goal: dict[str, str]) -> Problem:
    """One city, four places (c0-l0 the airport), a truck at c0-l0, p0 at c0-l1 and p1 at c0-l2."""
    facts = [atom("in_city", p, "c0") for p in PLACES] + [atom("airport", "c0-l0")]
    facts += [atom("serves", "truck0", "c0"), atom("at", "truck0", "c0-l0"),
              atom("at", "p0", "c0-l1"), atom("at", "p1", "c0-l2")]
    objects: dict[str, str | None] = {"c0": "city", "truck0": "truck", "p0": "package", "p1": "package"}
    objects |= {p: "location" for p in PLACES}
    return Problem(LOGISTICS, objects, State(facts), Goal.of([atom("at", k, v) for k, v in goal.items()],
                                                            LOGISTICS.rules), "one-city")


class Undoer:
    """Whenever p1 lies at c0-l2 (where it started, and where a restore puts it back), somebody
    carries it to c0-l0: the world undoes every restore of p1."""

    def __init__(self) -> None:
        self.calls = 0

    def __call__(self, state: State, rng: random.Random) -> list[Atom]:
        if not state.holds(atom("at", "p1", "c0-l2")):
            return []
        self.calls += 1
        return [atom("at", "p1", "c0-l2", value=False), atom("at", "p1", "c0-l0")]


def run(strategy: str, problem: Problem, world: SymbolicWorld, **kw: object) -> tuple[Executive, Monitor, Trace]:
    trace = Trace()
    with monitor_settings(MonitorConfig()):
        ex = Executive(problem, world, SymbolicBelief(problem.init),
                       parse_strategy(strategy, max_actions=300), seed=0, trace=trace, **kw)  # type: ignore[arg-type]
    ex.run()
    mon = next(m for m in ex.mechanisms if isinstance(m, Monitor))
    return ex, mon, trace


@pytest.mark.parametrize("strategy", ["hpn+monitor-restore", "hpn+monitor", "flat+monitor-restore"])
def test_a_world_that_undoes_every_restore_escalates_to_the_goal(strategy: str) -> None:
    prob = one_city({"p0": "c0-l3", "p1": "c0-l3"})
    undo = Undoer()
    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=undo, exogenous_prob=1.0)
    ex, mon, trace = run(strategy, prob, world)
    assert ex.metrics.outcome.value == "reached", ex.metrics.reason
    assert LOGISTICS.satisfies(world.state, prob.goal)
    assert undo.calls >= 2  # the world did undo a restore the agent had completed
    assert "the world undid a restore" in mon.stats.escalated
    notes = [e for e in trace.of("note") if e.get("escalation")]
    assert len(notes) == 1 and "for the rest of the run" in notes[0]["text"]
    # after the escalation every surprise is answered by replanning to the goal
    after = [e["alternative"] for e in trace.events[trace.events.index(notes[0]):]
             if e["event"] == "note" and e.get("alternative")]
    assert after and set(after) == {"goal"}


def test_monitor_goal_never_escalates() -> None:
    prob = one_city({"p0": "c0-l3", "p1": "c0-l3"})
    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=Undoer(), exogenous_prob=1.0)
    ex, mon, _ = run("hpn+monitor-goal", prob, world)
    assert ex.metrics.outcome.value == "reached" and mon.stats.escalated == ""


def test_a_goal_the_world_forbids_is_not_reached_and_says_why() -> None:
    """p1 must end where the world never lets it lie: no recovery exists; the run ends, before the
    action budget, with the reason."""
    prob = one_city({"p0": "c0-l2", "p1": "c0-l2"})
    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=Undoer(), exogenous_prob=1.0)
    ex, mon, _ = run("hpn+monitor-restore", prob, world)
    assert ex.metrics.outcome.value == "failed"
    assert "the world undid the goal 25 times" in ex.metrics.reason
    assert ex.metrics.actions < 300 and mon.stats.escalated


def test_a_cycle_escalates_and_replaces_the_repair_plans() -> None:
    """The progress guard's cycle (here handed over when the restore plan is on the stack)
    makes the monitor replace its repair plans by a plan to the goal, with the reason traced."""
    prob = one_city({"p0": "c0-l3", "p1": "c0-l3"})
    moved = []

    def once(state: State, rng: random.Random) -> list[Atom]:
        if moved or not state.holds(atom("at", "p0", "c0-l1")):
            return []
        moved.append(1)
        return [atom("at", "p0", "c0-l1", value=False), atom("at", "p0", "c0-l2")]

    seen: list[tuple[list[int], list[int]]] = []

    def on_action(ex: Executive, action: object) -> None:
        mon = next(m for m in ex.mechanisms if isinstance(m, Monitor))
        if mon._repairs and not mon.escalation.escalated and any(f.plan_id in mon._repairs for f in ex.stack):
            before = [f.plan_id for f in ex.stack]
            mon.after_cycle(ex, Cycle(2, 1, 0, 2))
            seen.append((before, [f.plan_id for f in ex.stack]))

    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=once, exogenous_prob=1.0)
    ex, mon, trace = run("hpn+monitor-restore", prob, world, on_action=on_action)
    assert ex.metrics.outcome.value == "reached", ex.metrics.reason
    assert moved and len(seen) == 1
    before, after = seen[0]
    assert not set(after[1:]) & mon._repairs and after[1:] != before[1:]  # the repair plan is gone
    assert "the progress guard found a cycle" in mon.stats.escalated
    assert any(r["trigger"] == "monitor" and r["reason"].startswith("goal:") for r in trace.of("replan"))


def test_escalation_bookkeeping() -> None:
    esc = Escalation()
    g = Goal.of([atom("at", "p1", "c0-l2")], LOGISTICS.rules)
    esc.chose(g)
    assert not esc.undone(g)
    esc.note(LOGISTICS, State([atom("at", "p1", "c0-l0")]))  # not reached yet
    assert not esc.undone(g)
    esc.note(LOGISTICS, State([atom("at", "p1", "c0-l2")]))
    assert esc.undone(g) and not esc.escalated
    esc.chose(None)
    assert not esc.undone(None)


def test_drop_loops_cuts_an_unload_and_load_again() -> None:
    prob = one_city({"p0": "c0-l3"})
    acts = {a.pddl(): a for a in ground_actions(LOGISTICS, prob.objects, prob.init)}
    seq = [acts[s] for s in ("(drive_truck truck0 c0-l0 c0-l1 c0)", "(load_truck p0 truck0 c0-l1 c0)",
                             "(unload_truck p0 truck0 c0-l1 c0)", "(load_truck p0 truck0 c0-l1 c0)",
                             "(drive_truck truck0 c0-l1 c0-l3 c0)", "(unload_truck p0 truck0 c0-l3 c0)")]
    states = simulate(LOGISTICS, prob.init, seq)
    assert states is not None
    out = drop_loops(states, seq)
    assert [a.pddl() for a in out] == ["(drive_truck truck0 c0-l0 c0-l1 c0)", "(load_truck p0 truck0 c0-l1 c0)",
                                       "(drive_truck truck0 c0-l1 c0-l3 c0)", "(unload_truck p0 truck0 c0-l3 c0)"]


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 10_000), length=st.integers(0, 40))
def test_drop_loops_keeps_a_valid_plan_to_the_same_end_without_revisits(seed: int, length: int) -> None:
    prob = generate(SIZES["tiny"], seed % 7)
    rng = random.Random(seed)
    ground = ground_actions(LOGISTICS, prob.objects, prob.init)
    state, walk = prob.init, []
    for _ in range(length):
        ok = [a for a in ground if all(LOGISTICS.holds(p, state) for p in a.preconditions(None))]
        if not ok:
            break
        a = rng.choice(ok)
        walk.append(a)
        state = state.apply(a.effects())
    states = simulate(LOGISTICS, prob.init, walk)
    assert states is not None
    out = drop_loops(states, walk)
    again = simulate(LOGISTICS, prob.init, out)
    assert again is not None and again[-1] == states[-1]
    assert len(set(again)) == len(again)  # no state twice
    it = iter(walk)
    assert all(any(a is b for b in it) for a in out)  # a subsequence of the walk


def test_flat_goal_plans_where_the_forward_search_applies() -> None:
    prob = one_city({"p0": "c0-l3", "p1": "c0-l3"})
    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=Undoer(), exogenous_prob=1.0)
    _, mon, _ = run("hpn+monitor-goal", prob, world)
    assert mon.stats.hierarchical_goal == ""  # logistics lists its facts: the flat plan is searched forward


def test_without_escalation_the_seeds_rule_chases_the_world() -> None:
    """``MonitorConfig(escalate=False)`` is the seed's rule as written (the reproduction of seed 003
    measures it): in the undoing world it restores until the action budget."""
    prob = one_city({"p0": "c0-l3", "p1": "c0-l3"})
    world = SymbolicWorld(LOGISTICS, prob.init, exogenous=Undoer(), exogenous_prob=1.0)
    trace = Trace()
    with monitor_settings(MonitorConfig(decision="restore", escalate=False)):
        ex = Executive(prob, world, SymbolicBelief(prob.init), parse_strategy("hpn+monitor-restore", max_actions=120),
                       seed=0, trace=trace)
    m = ex.run()
    mon = next(x for x in ex.mechanisms if isinstance(x, Monitor))
    assert m.outcome.value == "limit" and mon.stats.escalated == ""
    assert set(mon.stats.decisions) == {"restore"}


def test_under_hpn_the_goal_is_planned_at_the_strategys_levels_where_flat_would_regress() -> None:
    """Marsupial has generators, so a flat plan to the goal would be a regression search (up to
    50,000 LM-cut expansions, 30-60 s a call): the monitor plans the goal as HPN plans its root."""
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import Faults, apply_faults

    dom = get_domain("marsupial")
    ep = dom.scenario("single-3")(0)
    apply_faults(ep, Faults(failure=0.25))
    trace = Trace()
    with monitor_settings(MonitorConfig(decision="goal")):
        ex = Executive(ep.problem, ep.world, ep.belief, parse_strategy("hpn+monitor-goal", base_planner=dom.planner),
                       seed=0, trace=trace)
    m = ex.run()
    mon = next(x for x in ex.mechanisms if isinstance(x, Monitor))
    assert m.outcome.value == "reached", m.reason
    assert "searched by regression (operator " in mon.stats.hierarchical_goal
    assert "has a generator" in mon.stats.hierarchical_goal
    goal_plans = [e for e in trace.of("plan") if e["method"] == "goal"]
    assert goal_plans and mon.stats.decisions["goal"] == len(goal_plans)
    # abstract plans: the executive refined them (plans pushed below the monitor's)
    ids = {e["plan_id"] for e in goal_plans}
    assert any(e.get("parent") in ids for e in trace.of("plan"))
