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


def test_a_ground_skeleton_is_followed_step_by_step(monkeypatch: pytest.MonkeyPatch) -> None:
    """online+reuse on the shop: a flat plan of ~100 ground steps (no free variables) is replanned under
    its skeleton after each action; each step is the one instance its constants name (before: every
    achiever of every goal atom was grounded per step, and the pairwise ``excludes`` rule compared every
    two pre-image atoms, so the run used its 10 s on ~30 actions)."""
    scenarios = _shop(monkeypatch)
    from nowplan.acting.reuse import constrained_plan, skeleton  # noqa: PLC0415
    from nowplan.api import SymbolicBelief  # noqa: PLC0415

    prob = scenarios.problem(0)
    from nowplan.api import flat_levels  # noqa: PLC0415

    first = plan(prob.domain, prob.objects, SymbolicBelief(prob.init), prob.goal, flat_levels(),
                 PlannerConfig(engine="forward"))
    assert first.plan is not None and len(first.plan.actions) > 50
    tail = skeleton(first.plan.actions)
    res = constrained_plan(prob.domain, prob.objects, SymbolicBelief(prob.init), prob.goal, tail, time_budget=30.0)
    assert res.solved and res.plan is not None
    assert res.plan.actions == first.plan.actions
    m = run_episode(scenarios.episode(0), parse_strategy("online+reuse", max_actions=300), seed=0)
    assert m.outcome is Outcome.REACHED and m.goal_in_world is True


def test_an_effect_a_pairwise_rule_excludes_ends_the_regression(monkeypatch: pytest.MonkeyPatch) -> None:
    """``excludes(raw(b), turned(b))`` is a plain pairwise rule: a step whose effect makes ``raw(b)``
    true cannot precede a goal atom ``turned(b)`` it does not change (the pairs checked are the effects')."""
    scenarios = _shop(monkeypatch)
    from nowplan.api import Goal  # noqa: PLC0415
    from nowplan.planning.preimage import preimage  # noqa: PLC0415

    prob = scenarios.problem(0)
    dom = prob.domain
    turn = next(op for op in dom.operators if op.name == "turn")
    act = turn.instantiate(dict(zip(turn.params, ("gear1", "lathe"), strict=True)))
    assert preimage(Goal.of([atom("raw", "gear1")], dom.rules), act, None, dom) is None  # turn unsets raw
    kept = preimage(Goal.of([atom("turned", "gear1"), atom("turned", "gear2")], dom.rules), act, None, dom)
    assert kept is not None and atom("turned", "gear2") in kept.atoms and atom("raw", "gear1") in kept.atoms
