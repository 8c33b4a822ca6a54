"""HPN on a domain with one abstraction level (the kitchen declares no criticalities).

Its top level keeps every precondition, so HPN's calls plan the whole problem concretely, as a flat
strategy's do: they get the domain's goal-distance estimate.  Without it, kitchen cook seeds 0 and 2
failed under ``hpn`` with no faults (50,000 expansions of count-guided search without a plan).
"""

from __future__ import annotations

import pytest

from nowplan.acting.hpn import Executive
from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.logistics import episode


def test_a_domain_with_levels_keeps_hpn_calls_abstract() -> None:
    ep = episode("tiny", 0)
    ex = Executive(ep.problem, ep.world, ep.belief, parse_strategy("hpn"))
    assert not ex.single_level
    assert not ex.context().whole_problem
    flat = Executive(ep.problem, ep.world, ep.belief, parse_strategy("flat"))
    assert flat.single_level and flat.context().whole_problem


def test_a_domain_with_one_level_gives_hpn_its_estimate() -> None:
    pytest.importorskip("pybullet")
    from nowplan.domains.kitchen.tasks import make

    ep = make("cook", 0)
    ex = Executive(ep.problem, ep.world, ep.belief, parse_strategy("hpn"))
    assert ex.single_level
    ctx = ex.context()
    assert ctx.whole_problem
    assert ctx.extras["heuristic"] is ep.belief.planning_heuristic is not None


@pytest.mark.slow
@pytest.mark.parametrize("seed", [0, 2])
def test_hpn_cooks_on_the_seeds_it_failed_on(seed: int) -> None:
    pytest.importorskip("pybullet")
    from nowplan.domains.kitchen.tasks import make

    ep = make("cook", seed)
    m = run_episode(ep, parse_strategy("hpn", time_limit=300), seed=seed)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.action_counts["cook"] == 1 and m.action_counts["stove_off"] == 1
