"""Two more domains written against the public API only (examples/drone, examples/ward).

* ``drone``: a belief that is not a symbolic state (a Gaussian position estimate, a battery), every
  predicate a test of it, generators over continuous poses, an ``AtLeastRule`` battery whose need is
  regressed through flights by a generator that reads the goal, a ``ToleranceRule`` localization, a
  noisy position fix that may be missed, grasps that slip, gusts the drone does not feel; a
  ``SimulatedWorld`` (not symbolic) that tells its true state for the verdict.
* ``ward``: a ``ParticleBelief`` over doors that staff open and shut unseen and a trolley they push,
  door readings that are wrong or missing, a negative goal on a fluent only a look settles
  (``not open(d_iso)``) and one on an item's place (``not at(trolley, corridor)``), looks whose
  effects are hoped-for knowledge.

They found three engine bugs, each with a regression test (tests/test_generator_inputs.py,
tests/test_unknown_fluents.py): a generator called without its declared inputs, a negative literal
believed at odds of 1 in 2, and HPN quoting the planner's clamped time limit as the run's.
"""

from __future__ import annotations


import pytest

from nowplan.api import Outcome, ScenarioError, parse_strategy, run_episode
from nowplan.domains import registry
from nowplan.domains.registry import DomainSpec
from tests.helpers import EXAMPLES, example_spec
from tests.test_matrix import STRATEGIES

MONITORS = {"monitor", "monitor-cost", "monitor-goal", "monitor-restore", "monitor-rule-cost"}
# the monitor compares point states: the drone's belief is none; the ward's predicate maybe is a test
REFUSED = {"drone": ({"domain-planner"} | MONITORS, "domain-planner|not a point state"),
           "ward": ({"domain-planner"} | MONITORS, "domain-planner|tested on the belief")}
FAST = ["hpn", "flat", "online", "hpn+aggressive"]


def _spec(monkeypatch: pytest.MonkeyPatch, name: str) -> DomainSpec:
    return example_spec(monkeypatch, name)


def _run(monkeypatch: pytest.MonkeyPatch, name: str, strategy: str, seed: int) -> None:
    spec = _spec(monkeypatch, name)
    ep = spec.scenario(spec.matrix_scenario)(seed)
    st = parse_strategy(strategy, max_actions=300, time_limit=60.0)
    refused, match = REFUSED[name]
    if refused & set(strategy.split("+")):
        with pytest.raises(ScenarioError, match=match):
            run_episode(ep, st, seed=seed)
        return
    m = run_episode(ep, st, seed=seed)
    assert m.outcome is Outcome.REACHED, f"{strategy}: {m.outcome.value} ({m.reason})"
    assert m.goal_in_world is True and not m.disagreement


@pytest.mark.parametrize("name", ["drone", "ward"])
@pytest.mark.parametrize("strategy", FAST)
def test_the_main_strategies_reach_the_goal_in_the_world(monkeypatch: pytest.MonkeyPatch, name: str,
                                                          strategy: str) -> None:
    _run(monkeypatch, name, strategy, 0)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["drone", "ward"])
@pytest.mark.parametrize("strategy", [s for s in STRATEGIES if s not in FAST])
def test_every_strategy_reaches_the_goal_in_the_world(monkeypatch: pytest.MonkeyPatch, name: str,
                                                      strategy: str) -> None:
    _run(monkeypatch, name, strategy, 0)


@pytest.mark.parametrize("name", ["drone", "ward"])
def test_the_examples_are_plugins_with_entry_points(monkeypatch: pytest.MonkeyPatch, name: str) -> None:
    import tomllib  # noqa: PLC0415

    meta = tomllib.loads((EXAMPLES / name / "pyproject.toml").read_text())
    assert meta["project"]["entry-points"][registry.ENTRY_POINT_GROUP] == {name: f"{name}_domain:SPEC"}
    spec = _spec(monkeypatch, name)
    assert spec.name == name and spec.matrix_scenario in spec.scenarios and spec.model is not None


def test_the_drone_world_tells_its_true_state(monkeypatch: pytest.MonkeyPatch) -> None:
    """A world that is not symbolic judges success by its own state (Inspectable), read by the
    domain's tests: a drop short of the depot is not a delivery in the world."""
    from nowplan.api import Inspectable  # noqa: PLC0415

    spec = _spec(monkeypatch, "drone")
    ep = spec.scenario("deliver")(0)
    assert isinstance(ep.world, Inspectable)
    truth = ep.world.true_state()
    assert not spec.model.satisfies(truth, ep.problem.goal)


def test_a_shuttle_the_fingerprints_miss_is_a_stated_livelock(monkeypatch: pytest.MonkeyPatch) -> None:
    """drone-clean, flat, seed 3: the second parcel lies 0.39 from the depot, closer than the model's
    conflict rule separates two poses (2 x 0.25), so a flight to it and back looked free; the flat
    planner flew depot -> parcel -> depot 133 times, every flight a success, each leaving the battery
    and the spread a little different (no cycle), until the time limit.  The repeated block of actions
    is now a livelock with its reason, within a few rounds."""
    spec = _spec(monkeypatch, "drone")
    m = run_episode(spec.scenario("deliver")(3), parse_strategy("flat", max_actions=300, time_limit=60.0), seed=3)
    assert m.outcome is Outcome.LIVELOCK, (m.outcome, m.reason)
    assert m.reason.startswith("livelock: the same 2 actions ((fly (0.5, 0.5) (0.52, 0.11)") and m.actions < 40
