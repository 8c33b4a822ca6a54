"""The held-out mill shop (examples/millshop) through the public API: tidy-up goals and dead ends."""

from __future__ import annotations

import pytest

from nowplan.api import Outcome, atom, parse_strategy, run_episode
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan

from tests.helpers import example_spec


def _shop(monkeypatch: pytest.MonkeyPatch):  # noqa: ANN202
    example_spec(monkeypatch, "millshop")
    from millshop_domain import scenarios  # noqa: PLC0415

    return scenarios


def test_hpn_parks_the_agvs_once_at_the_end(monkeypatch: pytest.MonkeyPatch) -> None:
    """The goal parks both AGVs at the store and switches the machines off; no top-level step touches
    those atoms.  Owed at every pre-image (``maintain``, the seed's), every part ends with a drive home
    and the lathe switched off; owed at the end (the default, acting/postpone.py), HPN's run is about
    as long as flat planning's."""
    scenarios = _shop(monkeypatch)
    seed = 0
    flat = run_episode(scenarios.episode(seed), parse_strategy("flat", max_actions=300), seed=seed)
    hpn = run_episode(scenarios.episode(seed), parse_strategy("hpn", max_actions=300), seed=seed)
    kept = run_episode(scenarios.episode(seed), parse_strategy("hpn+maintain", max_actions=300), seed=seed)
    assert flat.outcome is hpn.outcome is Outcome.REACHED, hpn.reason
    assert hpn.goal_in_world is True
    assert hpn.actions <= 1.2 * flat.actions
    assert kept.actions > 1.5 * hpn.actions  # (194 against 90 at d621758)
    assert hpn.action_counts["power_off"] < kept.action_counts["power_off"]


def test_a_flat_call_hears_the_domains_dead_end(monkeypatch: pytest.MonkeyPatch) -> None:
    """Two shafts scrapped against three shaft orders: the domain's dead-end test answers a flat
    (forward) call as it answers the regression, instead of a search that runs out of nodes."""
    scenarios = _shop(monkeypatch)
    prob = scenarios.problem(0)
    shafts = sorted(str(p) for (p, k) in prob.init.facts("kind") if str(k) == "shaft")
    scrapped = prob.init.apply([f for p in shafts[:-1] for f in (
        atom("at", p, "store", value=False), atom("raw", p, value=False), atom("scrapped", p))])
    from nowplan.api import SymbolicBelief  # noqa: PLC0415

    wants = [str(k) for (_, k) in prob.init.facts("wants")]
    if wants.count("shaft") < 2:
        pytest.skip("this seed has fewer than two shaft orders")
    res = plan(prob.domain, prob.objects, SymbolicBelief(scrapped), prob.goal, None,
               PlannerConfig(engine="forward", max_nodes=50_000))
    assert res.status is PlanStatus.UNSOLVABLE and res.method == "dead_end"
    assert "shaft" in res.reason
