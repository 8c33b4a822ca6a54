"""The progress guard (nowplan.acting.progress) and success judged in the world."""

from __future__ import annotations

import pytest

from nowplan.acting.metrics import Outcome
from nowplan.acting.progress import CycleDetector, belief_fingerprint, situation
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Domain, Problem
from nowplan.core.state import State
from nowplan.domains.registry import Episode
from nowplan.trace import Trace
from nowplan.worlds.symbolic import SymbolicWorld

from corridor_domain import corridor
from test_mechanisms import CHAIN, PREDS, op


# -- the detector ---------------------------------------------------------------------------
def test_a_clean_return_is_a_cycle():
    d = CycleDetector()
    d.start("a")
    assert d.observe("b", succeeded=True, exogenous=False) is None
    cyc = d.observe("a", succeeded=True, exogenous=False)
    assert cyc is not None and cyc.length == 2 and cyc.count == 1 and cyc.first_visit == 0
    assert not d.livelocked
    assert "action 2" in cyc.describe() and "action 0" in cyc.describe()


def test_failed_retries_are_not_cycles():
    d = CycleDetector()
    d.start("a")
    for _ in range(10):  # a sticky door: the same situation after every failed try
        assert d.observe("a", succeeded=False, exogenous=False) is None
    assert d.cycles == 0


def test_a_return_caused_by_the_world_is_not_a_cycle():
    d = CycleDetector()
    d.start("a")
    d.observe("b", succeeded=True, exogenous=True)  # somebody moved something
    assert d.observe("a", succeeded=True, exogenous=False) is None
    # but a later clean return to "b" after the exogenous change is one
    assert d.observe("b", succeeded=True, exogenous=False) is not None


def test_livelock_after_max_cycles():
    d = CycleDetector(max_cycles=3)
    d.start("a")
    seen = []
    for s in ["b", "a", "b", "a"]:
        c = d.observe(s, succeeded=True, exogenous=False)
        seen.append(c is not None)
    assert seen == [False, True, True, True] and d.livelocked
    with pytest.raises(ValueError):
        CycleDetector(max_cycles=0)


def test_a_change_of_the_worlds_restarts_the_count_of_cycles():
    """Cycles each begun after the world undid the agent's work (a door shut as soon as it was
    opened) are not one loop of the agent's: the count restarts at every exogenous change."""
    d = CycleDetector(max_cycles=3)
    d.start("s")
    counts = []
    for _ in range(4):
        d.observe("s", succeeded=True, exogenous=True)  # opened the door; the world shut it
        d.observe("held", succeeded=True, exogenous=False)  # picked the sample up again
        c = d.observe("s", succeeded=True, exogenous=False)  # and set it down: a clean cycle
        counts.append(c.count if c is not None else 0)
    assert counts == [1, 1, 1, 1] and not d.livelocked
    # three clean cycles with no change of the world's in between are a livelock, as before
    for _ in range(2):
        d.observe("held", succeeded=True, exogenous=False)
        d.observe("s", succeeded=True, exogenous=False)
    assert d.livelocked


def test_fingerprints():
    st = State([atom("p")])
    assert belief_fingerprint(st) == st
    assert belief_fingerprint(SymbolicBelief(st)) == st

    class Own:
        def fingerprint(self):
            return ("mine", 1)

    assert belief_fingerprint(Own()) == ("mine", 1)
    assert belief_fingerprint(object()) is None
    assert situation(st, [Goal.of([atom("p")])]) == situation(State([atom("p")]), [Goal.of([atom("p")])])
    assert situation(st, [Goal.of([atom("p")])]) != situation(st, [Goal.of([atom("q")])])


# -- looping runs ---------------------------------------------------------------------------
# a trap: step2 "succeeds" but puts the robot back at the start; every strategy loops on it
TRAP = Domain("trap", PREDS, (
    op("step1", [("s0", 1)], ["s1"]),
    op("step2", [("s1", 1)], ["s2"]),
    op("step3", [("s2", 1)], ["s3"]),
))
TRAP_WORLD = Domain("trap-world", PREDS, (
    op("step1", [("s0", 1)], ["s1"]),
    op("step2", [("s1", 1)], ["s0"]),  # the world's step2 leads back to s0
    op("step3", [("s2", 1)], ["s3"]),
))


def _trap_episode():
    init = State([atom("s0")])
    prob = Problem(TRAP, {}, init, Goal.of([atom("s3")]))
    world = SymbolicWorld(TRAP_WORLD, init)

    class Undo:  # the world's state after step2 is s0 and not s1: apply the world's own effects
        def __init__(self) -> None:
            self.inner = world

        def execute(self, action):
            own = next(o for o in TRAP_WORLD.operators if o.name == action.name)
            return self.inner.execute(own.instantiate({}))

        def true_state(self):
            return self.inner.state

    return Episode(prob, Undo(), SymbolicBelief(init))


@pytest.mark.parametrize("strategy", ["hpn", "flat", "hpn+aggressive", "hpn+flexible+serendipity+selective",
                                      "online", "online+reuse"])
def test_a_livelock_ends_with_its_reason_within_three_cycles(strategy):
    tr = Trace()
    m = run_episode(_trap_episode(), parse_strategy(strategy), trace=tr)
    assert m.outcome is Outcome.LIVELOCK, (m.outcome, m.reason)
    assert m.reason.startswith("livelock: cycle 3 of at most 3")
    assert m.cycles == 3
    cycles = tr.of("cycle")
    assert len(cycles) == 3 and max(c["length"] for c in cycles) <= 4
    assert m.actions <= 4 + 3 * 4  # three cycles of at most 4 actions after the first pass, not a budget
    # after committing only cycles made since count: each starts where the previous one was seen
    assert all(b["n"] - b["length"] >= a["n"] for a, b in zip(cycles, cycles[1:]))
    assert tr.of("run_end")[0]["outcome"] == "livelock"


def test_the_cycle_bound_is_the_strategys():
    m = run_episode(_trap_episode(), parse_strategy("flat", max_cycles=1))
    assert m.outcome is Outcome.LIVELOCK and m.cycles == 1


def test_noise_is_not_taken_for_a_livelock():
    # failures and exogenous undoing come back to the same beliefs, but not by the agent's doing
    def undo(state, rng):
        return [atom("s1", value=False)] if state.value(("s1", ())) else []

    for seed in range(5):
        init = State([atom("s0")])
        prob = Problem(CHAIN, {}, init, Goal.of([atom("s3")]))
        world = SymbolicWorld(CHAIN, init, seed=seed, failure_prob=0.4, exogenous=undo, exogenous_prob=0.4)
        m = run_episode(Episode(prob, world, SymbolicBelief(init)), parse_strategy("hpn+flexible"), seed=seed)
        assert m.outcome is Outcome.REACHED, m.reason
        assert m.cycles == 0


# -- success judged in the world -------------------------------------------------------------
def test_reached_means_the_goal_holds_in_the_world():
    def steal(state, rng):  # the world undoes s3 unseen (the agent observes outcomes only)
        return [atom("s3", value=False)] if state.value(("s3", ())) else []

    init = State([atom("s0")])
    prob = Problem(CHAIN, {}, init, Goal.of([atom("s3")]))
    world = SymbolicWorld(CHAIN, init, exogenous=steal, exogenous_prob=1.0, observe="outcome")
    tr = Trace()
    m = run_episode(Episode(prob, world, SymbolicBelief(init)), parse_strategy("hpn"), trace=tr)
    assert m.goal_in_belief is True and m.goal_in_world is False
    assert m.outcome is Outcome.FAILED and "not in the world" in m.reason
    assert m.disagreement == ("s3()",) and m.to_dict()["disagreement"] == ["s3()"]
    assert tr.of("disagreement")[0]["atoms"] == ["s3()"]
    # without the theft belief and world agree and the run is reached
    world2 = SymbolicWorld(CHAIN, init, observe="outcome")
    ok = run_episode(Episode(prob, world2, SymbolicBelief(init)), parse_strategy("hpn"))
    assert ok.outcome is Outcome.REACHED and ok.goal_in_world is True and ok.disagreement == ()


# -- serendipity resumes forward only (tests/corridor_domain.py) ----------------------------------
@pytest.mark.parametrize("strategy", ["hpn+serendipity", "hpn+flexible+serendipity",
                                      "hpn+flexible+serendipity+selective"])
def test_serendipity_does_not_resume_a_step_behind_the_one_worked_on(strategy):
    tr = Trace()
    m = run_episode(corridor(), parse_strategy(strategy, max_actions=200), trace=tr)
    assert m.outcome is Outcome.REACHED, (m.outcome, m.reason)
    assert m.action_counts["unlock"] == 1 and m.actions <= 12
    plain = run_episode(corridor(), parse_strategy("hpn"))
    assert m.actions == plain.actions
    assert m.cycles == 0  # the forward-only rule, not the progress guard, keeps the key sub-plan


def test_aggressive_replanning_commits_after_a_cycle_in_the_corridor():
    # replanning from the root after every step walks back toward the locked door each time the
    # key sub-plan has taken a step away from it (the root's abstract plan ignores the lock, so it
    # looks cheaper than the rest of the current plans); the guard sees the cycle and commits
    tr = Trace()
    m = run_episode(corridor(), parse_strategy("hpn+aggressive", max_actions=200), trace=tr)
    assert m.outcome is Outcome.REACHED, (m.outcome, m.reason)
    assert m.cycles >= 1 and m.actions <= 20
    assert any("committing" in e["text"] for e in tr.of("note"))


@pytest.mark.parametrize("rest", [0.0, 1e9])
def test_aggressive_replanning_replaces_the_current_plans_only_with_a_cheaper_plan(monkeypatch, rest):
    # cost hysteresis: the root's new plan is taken only if it costs less than the rest of the
    # current plans; priced at 0 the current plans always go on, priced dear they are always replaced
    import nowplan.acting.aggressive as aggressive

    monkeypatch.setattr(aggressive, "rest_cost", lambda ex: rest)
    tr = Trace()
    m = run_episode(corridor(), parse_strategy("hpn+aggressive", max_actions=200), trace=tr)
    assert m.outcome is Outcome.REACHED, (m.outcome, m.reason)
    replaced = [e for e in tr.of("pop") if e["reason"] == "replaced"]
    kept = [e for e in tr.of("plan_failed") if e["reason"].startswith("aggressive:")]
    if rest == 0.0:
        assert kept and not replaced and m.cycles == 0
        assert all("the current plan goes on" in e["reason"] for e in kept)
    else:
        assert replaced and not kept


def test_forget_keeps_the_present_situation():
    d = CycleDetector()
    d.start("a")
    d.observe("b", succeeded=True, exogenous=False)
    assert d.observe("a", succeeded=True, exogenous=False) is not None
    d.forget(keep="a")  # committed: earlier visits no longer count, the present one does
    assert d.observe("b", succeeded=True, exogenous=False) is None
    assert d.observe("a", succeeded=True, exogenous=False) is not None and d.cycles == 2
    d.forget(cycles=True)
    assert d.cycles == 0 and d.observe("a", succeeded=True, exogenous=False) is None


def test_a_cycle_with_a_failure_commits_but_does_not_count_toward_a_livelock():
    d = CycleDetector(max_cycles=1)
    d.start("a")
    d.observe("b", succeeded=True, exogenous=False)
    d.observe("b", succeeded=False, exogenous=False)  # a failed step made the agent change its mind
    cyc = d.observe("a", succeeded=True, exogenous=False)
    assert cyc is not None and not cyc.clean and "some failed" in cyc.describe()
    assert d.seen == 1 and d.cycles == 0 and not d.livelocked
    assert d.observe("b", succeeded=True, exogenous=False).clean and d.livelocked


def test_an_action_the_world_always_refuses_ends_stalled_not_by_the_budget():
    for strategy in ("hpn", "hpn+flexible", "online"):
        init = State([atom("s0")])
        prob = Problem(CHAIN, {}, init, Goal.of([atom("s3")]))
        world = SymbolicWorld(CHAIN, init, failure_prob=1.0)
        m = run_episode(Episode(prob, world, SymbolicBelief(init)), parse_strategy(strategy, max_stalls=10))
        assert m.outcome is Outcome.FAILED and m.reason.startswith("stalled: (step1) failed 10 times"), m.reason
        assert "injected failure" in m.reason and m.actions <= 11  # not the 1 000-action budget
    d = CycleDetector()
    d.start("a")
    for _ in range(3):
        d.observe("a", succeeded=False, exogenous=False)
    assert d.stalled == 3
    d.observe("a", succeeded=True, exogenous=False)
    assert d.stalled == 0
