"""Every strategy in a house (tests/locked_house.py): rooms, doors, a locked door and its key,
sticky doors failing at 0.2, a misplaced mug found by looking; judged in the world."""

from __future__ import annotations

import pytest

from locked_house import episode

from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy

STRATEGIES = (
    "hpn", "flat", "hpn+flexible", "hpn+serendipity", "hpn+flexible+serendipity", "hpn+aggressive",
    "flat+aggressive", "hpn+selective", "hpn+flexible+serendipity+selective", "hpn+monitor",
    "hpn+monitor-goal", "online", "online+reuse",
)


def _run(strategy: str, seed: int):
    return run_episode(episode(seed), parse_strategy(strategy, time_limit=60.0), seed=seed)


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_house_small(strategy):
    for seed in (0, 1, 3):  # the mug in the garage behind the locked door (1, 3) or in the study (0)
        m = _run(strategy, seed)
        assert m.outcome is Outcome.REACHED, (strategy, seed, m.outcome, m.reason)
        assert m.goal_in_world is True and m.disagreement == ()


@pytest.mark.slow
@pytest.mark.parametrize("strategy", STRATEGIES)
def test_house_sweep(strategy):
    runs = [_run(strategy, seed) for seed in range(20)]
    bad = [(s, m.outcome.value, m.reason) for s, m in enumerate(runs) if m.outcome is not Outcome.REACHED]
    assert len(bad) <= 1, bad  # >= 95 % of 20 seeds
    # a run that does not reach the goal says why, never by a budget alone
    assert all(m.outcome is not Outcome.LIMIT for m in runs), bad


def test_the_mug_is_found_by_looking_and_the_key_fetched():
    m = _run("hpn", 1)
    assert m.action_counts["look"] >= 2  # looked where it was believed, then elsewhere
    assert m.action_counts["unlock"] == 1
