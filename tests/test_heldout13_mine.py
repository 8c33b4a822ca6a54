"""The held-out mine example (examples/mine) through the public API: a couple of seeded runs."""

from __future__ import annotations

import pytest

from nowplan.api import Outcome, parse_strategy, run_episode

from tests.helpers import example_spec


@pytest.mark.parametrize("seed", [0, 1])
def test_flat_finds_and_stores_the_gem_with_a_noisy_detector(monkeypatch: pytest.MonkeyPatch, seed: int) -> None:
    spec = example_spec(monkeypatch, "mine")
    m = run_episode(spec.scenario("noisy")(seed), parse_strategy("flat", max_actions=150), seed=seed)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
