"""A held-out domain written against the public API only: examples/greenhouse (helper heldout12).

Two robots water plants from a shared tank of discrete levels (two taps, one pump use: a leak can
leave no plan) and rid them of pests that a noisy sensor reports; one sprayer, fetched from the
shed, with charges that are never refilled; poses proposed by goal-free generators
(``Generator(reads=reads_nothing)``); a particle belief over the pests, ``maybe_clean`` and
``vacant`` tests of it.  benchmarks/results/heldout12/README.md has its runs and what they found.
"""

from __future__ import annotations


import pytest

from nowplan.api import NowplanError, Outcome, parse_strategy, run_episode
from nowplan.domains.registry import DomainSpec
from tests.helpers import example_spec


def _spec(monkeypatch: pytest.MonkeyPatch) -> DomainSpec:
    return example_spec(monkeypatch, "greenhouse")


def test_two_plants_with_a_noisy_sensor_are_tended_in_the_world(monkeypatch: pytest.MonkeyPatch) -> None:
    """hpn on the matrix scenario (sensor noise 0.15), seed 1: inspections, the sprayer, two fills
    around the one pump use (at 766fd5d the lazy relaxation called two sprays a dead end here)."""
    spec = _spec(monkeypatch)
    m = run_episode(spec.scenario(spec.matrix_scenario)(1), parse_strategy("hpn", max_actions=100, time_limit=30),
                    seed=1)
    assert m.outcome is Outcome.REACHED, (m.outcome, m.reason)
    assert m.goal_in_world is True and not m.disagreement
    assert m.action_counts["fill"] == 2 and m.action_counts["pump"] == 1


def test_a_leak_after_the_pump_is_a_dead_end_named(monkeypatch: pytest.MonkeyPatch) -> None:
    """Leaks and pests (p 0.2), seed 0: the tank leaks after its one refill; the run says which plant
    can no longer be watered instead of "search space exhausted" alone."""
    from greenhouse_domain.scenarios import episode

    _spec(monkeypatch)
    m = run_episode(episode(0, exogenous_prob=0.2, noise=0.2), parse_strategy("hpn", max_actions=100, time_limit=30),
                    seed=0)
    assert m.outcome is Outcome.FAILED, (m.outcome, m.reason)
    assert "no plan even for watered(p2) alone" in m.reason, m.reason


@pytest.mark.parametrize("strategy", ["hpn+monitor", "hpn+domain-planner"])
def test_what_the_domain_cannot_support_is_refused_in_one_line(monkeypatch: pytest.MonkeyPatch,
                                                               strategy: str) -> None:
    spec = _spec(monkeypatch)
    with pytest.raises(NowplanError) as e:
        run_episode(spec.scenario("tend")(0), parse_strategy(strategy, max_actions=10), seed=0)
    assert "\n" not in str(e.value) and len(str(e.value)) < 300
