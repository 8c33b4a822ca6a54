"""One progress guard (nowplan.acting.guard) for both acting loops: the executive and the online policy."""

from __future__ import annotations

from typing import Any

import pytest

import nowplan.acting.online as online_module
from nowplan.acting.guard import ProgressGuard
from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.progress import Cycle
from nowplan.acting.run import make_runner, run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.state import State
from nowplan.trace import Trace
from nowplan.worlds.base import Observation

from test_mechanisms import CHAIN
from test_progress import _trap_episode


def test_the_online_policy_and_the_executive_hold_the_same_guard():
    for strategy in ("hpn", "online", "online+reuse+deferred"):
        runner = make_runner(_trap_episode(), parse_strategy(strategy))
        assert type(runner.guard) is ProgressGuard
    # the online policy's own copy of the guard's logic is gone
    for name in ("CycleDetector", "RepeatedActions", "stall_reason", "failed_cycles_reason"):
        assert not hasattr(online_module, name), name


@pytest.mark.parametrize("strategy, actor, commitment", [
    ("online", "the policy", "committing to the current plan ("),
    ("online+reuse", "the policy", "committing to the current plan ("),
    ("hpn", "the executive", "committing to the current plans (no reconsideration until"),
])
def test_a_cycle_commits_and_cycles_while_committed_end_as_a_livelock(strategy, actor, commitment):
    tr = Trace()
    ep = _trap_episode()
    runner = make_runner(ep, parse_strategy(strategy), trace=tr)
    m = runner.run()
    # the trap's step2 brings the agent back to the start: cycle 1 commits, cycle 2 (made while
    # committed) commits again, cycle 3 is the livelock, well before any budget
    assert m.outcome is Outcome.LIVELOCK, m.reason
    assert m.reason.startswith("livelock: cycle 3 of at most 3: ")
    assert m.reason.endswith(f"although {actor} had committed to its plan")
    assert m.cycles == 3 and len(tr.of("cycle")) == 3 and m.actions <= 16
    notes = [e["text"] for e in tr.of("note")]
    commits = [t for t in notes if t.startswith("progress: ") and commitment in t]
    assert len(commits) == 2, notes  # the cycle that ends the run is not committed to
    assert runner.guard.committed
    if strategy.startswith("online"):
        # the plan committed to is followed while its next step applies (in the trap it never does:
        # step2 leaves the belief where step3 is not applicable, so the policy replans each time)
        assert "progress: commitment ends (the committed plan's next step is not applicable)" in notes
        assert all("committing to the current plan (1 action(s))" in t for t in commits)


def test_the_executive_and_the_online_policy_decide_alike_in_the_trap():
    seen = {}
    for strategy in ("flat", "online"):
        m = run_episode(_trap_episode(), parse_strategy(strategy))
        seen[strategy] = (m.outcome, m.cycles, m.reason.split(", although")[0])
    assert seen["flat"][:2] == seen["online"][:2] == (Outcome.LIVELOCK, 3)


# -- the guard's rules, with a scripted host ------------------------------------------------------
class _Host:
    """A GuardHost whose belief is set by hand: one atom of the chain domain at a time."""

    actor = "the host"

    def __init__(self, max_cycles: int) -> None:
        self.strategy = parse_strategy("hpn", max_cycles=max_cycles)
        self.guard = ProgressGuard(max_cycles)
        self.trace = Trace()
        self.metrics = Metrics()
        self.domain = CHAIN
        self.problem = Problem(CHAIN, {}, State([atom("s0")]), Goal.of([atom("s3")]))
        self.belief = State([atom("s0")])
        self.last_action: Any = None
        self.last_failed: Any = None
        self.heard: list[Cycle] = []
        self.commits: list[Cycle] = []
        self.guard.start(self)

    @property
    def truth(self) -> Any:
        return self.belief

    def situation(self) -> Any:
        return self.guard.situation(self, self.belief, (self.problem.goal,))

    def after_cycle(self, cyc: Cycle) -> None:
        self.heard.append(cyc)

    def commit(self, cyc: Cycle) -> str:
        self.commits.append(cyc)
        return "committing (scripted)"

    def end_commitment(self) -> str:
        return "the commitment ends (scripted)"

    def act(self, *names: str) -> tuple[Outcome, str] | None:
        """One successful action after which the belief holds ``names``."""
        self.belief = State([atom(n) for n in names])
        self.last_action = CHAIN.operators[self.metrics.actions % 2].instantiate({})
        self.metrics.actions += 1
        return self.guard.watch(self, Observation(success=True))

    def notes(self) -> list[str]:
        return [e["text"] for e in self.trace.of("note")]


def test_a_livelock_within_max_cycles_while_committed():
    h = _Host(max_cycles=2)
    assert h.act("s1") is None
    assert h.act("s0") is None  # cycle 1: heard, committed to
    assert len(h.heard) == len(h.commits) == 1 and h.guard.committed
    assert h.notes()[-1].startswith("progress: the belief and the plan stack's goals after action 2 are those "
                                    "after action 0") and h.notes()[-1].endswith("; committing (scripted)")
    assert h.act("s1") is None  # the situations before the commitment are forgotten: not a cycle
    stop = h.act("s0")  # cycle 2, made while committed: the livelock
    assert stop is not None and stop[0] is Outcome.LIVELOCK
    assert stop[1].startswith("livelock: cycle 2 of at most 2: ") and stop[1].endswith(
        "although the host had committed to its plan")
    assert len(h.heard) == 2 and len(h.commits) == 1  # heard of, but not committed to
    assert h.metrics.cycles == 2


def test_progress_ends_the_commitment_and_restarts_the_count_of_cycles():
    h = _Host(max_cycles=2)
    h.act("s1")
    h.act("s0")  # cycle 1: committed
    assert h.act("s2") is None  # a belief never held before: progress
    assert not h.guard.committed and h.guard.cycles.cycles == 0
    assert h.notes()[-1] == "progress: a belief not held before; the commitment ends (scripted)"
    assert h.act("s0") is None  # the situations before the progress are forgotten too
    assert h.act("s2") is None and h.guard.committed  # cycle 1 again since the progress: committed
    assert len(h.commits) == 2 and h.commits[-1].count == 1
    assert h.act("s0") is None
    stop = h.act("s2")
    assert stop is not None and stop[1].startswith("livelock: cycle 2 of at most 2: ")
