"""The held-out tidy example (examples/tidy) through the public API: a couple of seeded runs."""

from __future__ import annotations

import pytest

from nowplan.api import Outcome, parse_strategy, run_episode

from tests.helpers import example_spec


@pytest.mark.parametrize("seed", [0, 1])
def test_flat_tidies_the_house_behind_a_locked_door(monkeypatch: pytest.MonkeyPatch, seed: int) -> None:
    """Three things put away, one stacked under the others, one behind a door whose key lies
    under a cup: flat plans it all at once and the world agrees."""
    spec = example_spec(monkeypatch, "tidy")
    m = run_episode(spec.scenario("tidy")(seed), parse_strategy("flat", max_actions=150), seed=seed)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
    assert m.action_counts["call_owner"] == 0  # the owner (cost 40) is dearer than the key


def test_hpn_tidies_with_a_gripper_that_fails_and_drops(monkeypatch: pytest.MonkeyPatch) -> None:
    spec = example_spec(monkeypatch, "tidy")
    m = run_episode(spec.scenario("clumsy")(0), parse_strategy("hpn", max_actions=200), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.goal_in_world is True
