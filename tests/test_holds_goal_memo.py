"""Executive.holds_goal (acting/hpn.py) remembers goal tests per State: every answer during runs with
action failures equals a fresh Domain.satisfies on the current truth, and repeated tests are answered
from the memo."""

from __future__ import annotations

from typing import Any

import pytest

import nowplan.acting.hpn as hpn_mod
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.logistics.scenarios import episode


@pytest.mark.parametrize("strategy", ["hpn", "hpn+flexible+serendipity"])
def test_every_remembered_answer_is_the_fresh_one(monkeypatch: pytest.MonkeyPatch, strategy: str) -> None:
    real = hpn_mod.Executive.holds_goal
    asked: list[int] = []

    def checked(self: Any, goal: Any) -> bool:
        got = real(self, goal)
        assert got == self.domain.satisfies(self.truth, goal)
        asked.append(1)
        return got

    monkeypatch.setattr(hpn_mod.Executive, "holds_goal", checked)
    m = run_episode(episode("medium", seed=3, failure_prob=0.3), parse_strategy(strategy), seed=3)
    assert m.outcome.value == "reached" and asked


def test_repeated_tests_in_one_state_are_not_recomputed(monkeypatch: pytest.MonkeyPatch) -> None:
    from nowplan.core.domain import Domain

    calls: list[tuple[int, int]] = []
    orig = Domain.satisfies

    def counting(self: Domain, belief: Any, goal: Any) -> bool:
        calls.append((id(belief), id(goal)))
        return orig(self, belief, goal)

    monkeypatch.setattr(Domain, "satisfies", counting)
    run_episode(episode("medium", seed=1), parse_strategy("hpn"), seed=1)
    ex_calls = len(calls)
    calls.clear()
    monkeypatch.setattr(hpn_mod.Executive, "holds_goal",
                        lambda self, goal: self.domain.satisfies(self.truth, goal))  # no memo
    run_episode(episode("medium", seed=1), parse_strategy("hpn"), seed=1)
    assert ex_calls < len(calls)  # the memo answered some tests without a new satisfies call
