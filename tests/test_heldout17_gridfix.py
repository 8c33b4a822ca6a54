"""The held-out feeder restoration (examples/gridfix) through the public API: flat, HPN and flexible HPN
reach the goal on a clean storm, and a noisy run is the same for the same seed
(benchmarks/results/heldout17/README.md has the whole matrix and what it found)."""

from __future__ import annotations

import pytest

from nowplan.api import Outcome, parse_strategy, run_episode
from tests.helpers import example_spec


@pytest.mark.parametrize("strategy", ["flat", "hpn", "hpn+flexible"])
def test_a_clean_storm_is_restored(monkeypatch: pytest.MonkeyPatch, strategy: str) -> None:
    example_spec(monkeypatch, "gridfix")
    from gridfix_domain import scenarios  # noqa: PLC0415

    m = run_episode(scenarios.episode(0), parse_strategy(strategy, max_actions=200), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True


def test_the_same_seed_gives_the_same_run(monkeypatch: pytest.MonkeyPatch) -> None:
    example_spec(monkeypatch, "gridfix")
    from gridfix_domain import scenarios  # noqa: PLC0415

    runs = [run_episode(scenarios.episode(1, miss=0.15, fp=0.1), parse_strategy("hpn", max_actions=200), seed=1)
            for _ in range(2)]
    assert runs[0].actions == runs[1].actions and runs[0].execution_cost == runs[1].execution_cost
