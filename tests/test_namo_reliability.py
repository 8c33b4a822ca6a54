"""NAMO reliability: failed moves and grasps, noisy looks, late obstacles never crash or loop."""

from __future__ import annotations

from dataclasses import replace

import pytest

pytest.importorskip("shapely")

from nowplan.acting.metrics import Outcome  # noqa: E402
from nowplan.acting.run import run_episode  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.domains.namo.maps import BUILTIN  # noqa: E402
from nowplan.domains.namo.scenarios import episode  # noqa: E402
from nowplan.domains.namo.spec import parse  # noqa: E402
from nowplan.trace import Trace  # noqa: E402

STRATEGIES = [
    "hpn+foresight",
    "hpn+foresight+aggressive",
    "hpn+foresight+selective",
    "hpn+flexible+serendipity+foresight+selective",
]
# a run that loops is bounded by its budgets; a loop outside them fails on this time-out
pytestmark = pytest.mark.timeout(120)

MAX_ACTIONS = 60
MAX_PLANS = 400


def perturbed(name: str, **noise: float):
    spec = parse(BUILTIN[name])
    sensor_keys = {"miss_prob", "sigma_per_m"}
    spec = replace(
        spec,
        noise=replace(spec.noise, **{k: v for k, v in noise.items() if k not in sensor_keys}),
        sensor=replace(spec.sensor, **{k: v for k, v in noise.items() if k in sensor_keys}),
    )
    return spec


def bounded_run(spec, strategy: str, seed: int):
    ep = episode(spec, seed)
    tr = Trace()
    m = run_episode(ep, parse_strategy(strategy, max_actions=MAX_ACTIONS, max_plans=MAX_PLANS), seed=seed, trace=tr)
    # a loop would end the run by spending its action or planning budget (counts, not time):
    # every run must end before either is spent
    assert m.actions < MAX_ACTIONS and m.plans_made + m.plan_failures < MAX_PLANS, (m.outcome, m.reason)
    if m.outcome is not Outcome.REACHED:
        assert m.reason  # every unfinished run says why
    assert tr.events[-1]["event"] == "run_end"
    return ep, m, tr


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_failed_moves_and_grasps(strategy):
    spec = perturbed("corridor", move_fail=0.25, grasp_fail=0.3)
    failures = 0
    reached = 0
    for seed in range(3):
        ep, m, _ = bounded_run(spec, strategy, seed)
        failures += ep.world.failures
        reached += m.outcome is Outcome.REACHED
    assert failures > 0  # the perturbation really happened
    assert reached >= 2


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_noisy_looks(strategy):
    spec = perturbed("fig6", miss_prob=0.4, sigma_per_m=0.05)
    reached = sum(bounded_run(spec, strategy, seed)[1].outcome is Outcome.REACHED for seed in range(3))
    assert reached >= 2


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_an_obstacle_that_appears_late(strategy):
    data = dict(BUILTIN["fig6"])
    data["objects"] = [*data["objects"], {"name": "late", "at": [2.4, 1.6], "appear_after": 2}]
    ep, m, tr = bounded_run(parse(data), strategy, 0)
    assert tr.of("exogenous")  # it did appear
    assert m.outcome is Outcome.REACHED, m.reason
    assert "late" in ep.belief.objects  # and the robot found it (by looking or bumping)


def test_an_unreachable_goal_ends_with_a_reason():
    data = dict(BUILTIN["simple"])
    data["walls"] = [[4.0, 0.0, 4.2, 3.0]]  # a wall across the room
    ep, m, _ = bounded_run(parse(data), "hpn+foresight", 0)
    assert m.outcome is Outcome.FAILED and "no plan" in m.reason
