"""Every domain × every strategy switch, end to end on a small seeded scenario.

Each registered switch is run on every registered domain (alone on top of
``hpn``, or as the online policy for seed 004's switches, plus the papers'
combinations).  A run either reaches its goal — and on a symbolic world the
goal holds in the *true* state, not only in the belief — or the combination is
one a domain declares it cannot support, which must be refused up front with a
:class:`ScenarioError` naming the switch.  The refusals are listed here, so a
switch that silently stops working on a domain fails this test.  A user's domain found as a
plugin (a pip-installed example) runs too, but need not suit every strategy: it must refuse in
one line naming the switch, or end within the budget with a reason, and never claim a goal the
world does not hold.

Logistics, marsupial and NAMO run in the default suite (well under a second
each); pieces and the PyBullet kitchen take seconds per run and are marked slow.
"""

from __future__ import annotations

import pytest

from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy, strategy_names
from nowplan.domains.registry import domain_names, get_domain
from nowplan.errors import ScenarioError

# each domain declares the small seeded scenario the matrix runs (DomainSpec.matrix_scenario)
SCENARIOS = {d: get_domain(d).matrix_scenario or get_domain(d).default_scenario for d in domain_names()}
SLOW = {d for d in domain_names() if get_domain(d).matrix_slow}
# the domains shipped in src/ (each must reach its goal under every switch it does not refuse)
BUILT_IN = {d for d in domain_names() if get_domain(d).source.split("=")[-1].strip().startswith("nowplan.")}
ONLINE = ("online", "reuse", "deferred")
MONITORS = ("monitor", "monitor-goal", "monitor-restore", "monitor-cost", "monitor-rule-cost")


def _spec(switch: str) -> str:
    if switch in ("hpn", "flat", "online"):
        return switch
    return f"online+{switch}" if switch in ONLINE else f"hpn+{switch}"


STRATEGIES = sorted({_spec(s) for s in strategy_names()}) + [
    "hpn+flexible+serendipity+selective+foresight",  # seed 000's selective BHPN
    "flat+flexible+serendipity",
    "hpn+peephole+flexible",  # seed 002's RCHPN with flexible execution
    "online+reuse+deferred",  # seed 004's "Both"
]

# (domain, switch) pairs refused before the run, with a reason
REFUSED = {
    ("marsupial", s) for s in ("flat", *ONLINE)  # the loader is planned in the now
} | {
    (d, m) for d in ("namo", "kitchen") for m in MONITORS  # no point belief to compare
} | {
    (d, "domain-planner") for d in ("logistics", "marsupial", "namo", "kitchen")  # no planner of its own
}


def _refusal(domain: str, strategy: str) -> str | None:
    for switch in strategy.split("+"):
        if (domain, switch) in REFUSED:
            return switch
    return None


def _cases() -> list[object]:
    out: list[object] = []
    for d in domain_names():
        marks = [pytest.mark.slow] if d in SLOW else []
        for s in STRATEGIES:
            out.append(pytest.param(d, s, marks=marks, id=f"{d}-{s}"))
    return out


def test_every_domain_declares_a_matrix_scenario_it_has() -> None:
    for d in domain_names():
        spec = get_domain(d)
        assert SCENARIOS[d] in spec.scenarios, (d, SCENARIOS[d])
    # the built-in domains are found as plugins, like a user's
    assert {"logistics", "marsupial", "namo", "pieces", "kitchen"} <= set(domain_names())
    assert {"logistics", "marsupial", "namo", "pieces", "kitchen"} <= BUILT_IN


@pytest.mark.parametrize(("domain", "strategy"), _cases())
def test_domain_strategy(domain: str, strategy: str) -> None:
    spec = get_domain(domain)
    episode = spec.scenario(SCENARIOS[domain])(0)
    st = parse_strategy(strategy, max_actions=200, time_limit=60.0)
    refused = _refusal(domain, strategy)
    if refused is None and "domain-planner" in strategy.split("+") and episode.problem.domain.planner is None:
        refused = "domain-planner"  # a plugin domain (e.g. examples/house once pip-installed) without a planner
    if refused is not None:
        with pytest.raises(ScenarioError) as err:
            run_episode(episode, st, seed=0)
        msg = str(err.value)
        assert domain in msg and ("monitor" in msg or f"'{refused}'" in msg)
        return
    if domain not in BUILT_IN:
        try:
            m = run_episode(episode, st, seed=0)
        except ScenarioError as e:  # a user's domain may refuse a switch up front: in one line naming it
            assert any(sw.split("-")[0] in str(e) for sw in strategy.split("+")[1:]), (strategy, str(e))
            return
    else:
        m = run_episode(episode, st, seed=0)
    if domain not in BUILT_IN and m.outcome is not Outcome.REACHED:
        # a user's domain (a pip-installed example) need not suit every strategy (examples/mine's
        # hierarchy is not downward refinable, so plain hpn gives up): it must end with a reason,
        # within the action budget, and never claim the goal
        assert m.reason and m.actions <= 200, f"{domain} × {strategy}: {m.outcome.value} ({m.reason})"
        assert m.goal_in_world is not True
        return
    assert m.outcome is Outcome.REACHED, f"{domain} × {strategy}: {m.outcome.value} ({m.reason})"
    assert 0 < m.actions <= 200
    true_state = getattr(episode.world, "state", None)
    if hasattr(true_state, "facts"):  # a symbolic world: the goal holds in the world itself
        assert episode.problem.domain.satisfies(true_state, episode.problem.goal)
