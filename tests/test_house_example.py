"""The tutorial's house domain (examples/house) as a plugin, under every strategy of the matrix.

It is found the way a user's domain is: through ``NOWPLAN_DOMAINS`` with the
example's directory on the path (the in-process tests), through ``nowplan
--import`` (the CLI test), and its pyproject declares the entry point that
``pip install examples/house`` registers (checked against the module's SPEC).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains import registry
from nowplan.domains.registry import DomainSpec
from nowplan.errors import ModelError, ScenarioError
from tests.helpers import example_spec
from tests.test_matrix import STRATEGIES

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "house"
REFUSED = {"domain-planner"}  # the house has no planner of its own


@pytest.fixture()
def house(monkeypatch: pytest.MonkeyPatch) -> DomainSpec:
    return example_spec(monkeypatch, "house")


def test_the_example_is_a_plugin_with_an_entry_point(house: DomainSpec) -> None:
    meta = tomllib.loads((EXAMPLE / "pyproject.toml").read_text())
    eps = meta["project"]["entry-points"][registry.ENTRY_POINT_GROUP]
    assert eps == {"house": "house_domain:SPEC"}
    # found through NOWPLAN_DOMAINS, or through its entry point once `pip install -e examples/house` ran
    assert house.source in ("module house_domain", "entry point house = house_domain:SPEC"), house.source
    assert house.name == "house"
    assert house.matrix_scenario in house.scenarios and house.renderer is not None
    assert house.model is not None and house.model.name == "house"


def test_model_world_and_scenarios_fit_in_150_lines() -> None:
    files = [EXAMPLE / "house_domain" / f for f in ("model.py", "world.py", "scenarios.py")]
    assert sum(len(f.read_text().splitlines()) for f in files) <= 150


@pytest.mark.parametrize("strategy", STRATEGIES)
def test_house_under_every_strategy(house: DomainSpec, strategy: str) -> None:
    episode = house.scenario(house.matrix_scenario)(0)
    st = parse_strategy(strategy, max_actions=200, time_limit=60.0)
    if REFUSED & set(strategy.split("+")):
        with pytest.raises(ScenarioError, match="domain-planner"):
            run_episode(episode, st, seed=0)
        return
    m = run_episode(episode, st, seed=0)
    assert m.outcome is Outcome.REACHED, f"{strategy}: {m.outcome.value} ({m.reason})"
    assert episode.problem.domain.satisfies(episode.world.state, episode.problem.goal)  # type: ignore[attr-defined]


@pytest.mark.parametrize("scenario", ["fetch", "sticky", "draughty"])
def test_house_faults_happen_and_are_overcome(house: DomainSpec, scenario: str) -> None:
    failures = exogenous = 0
    for seed in range(6):
        ep = house.scenario(scenario)(seed)
        m = run_episode(ep, parse_strategy("hpn", max_actions=200), seed=seed)
        assert m.outcome is Outcome.REACHED, (scenario, seed, m.reason)
        failures += ep.world.failures  # type: ignore[attr-defined]
        exogenous += ep.world.exogenous_events  # type: ignore[attr-defined]
    assert (failures > 0) == (scenario == "sticky")
    assert (exogenous > 0) == (scenario == "draughty")


def test_an_initial_state_with_the_robot_in_two_rooms_is_refused(house: DomainSpec) -> None:
    from house_domain.model import DOMAIN  # type: ignore[import-not-found]
    from house_domain.scenarios import problem  # type: ignore[import-not-found]

    from nowplan.api import Problem, State, atom

    p = problem(0)
    two_rooms = State([*p.init.atoms(), atom("robot_in", "study")])
    with pytest.raises(ModelError, match=r"robot_in.*exactly_one\('robot_in', key=\(\)\)"):
        Problem(DOMAIN, p.objects, two_rooms, p.goal, "two-rooms")
    no_cup = State([a for a in p.init.atoms() if a.args[:1] != ("cup",)])
    with pytest.raises(ModelError, match="no at or holding atom for 'cup'"):
        Problem(DOMAIN, p.objects, no_cup, p.goal, "no-cup")


def test_the_cli_runs_renders_and_fails_the_house(tmp_path: Path) -> None:
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(EXAMPLE), *sys.path])}
    env.pop("NOWPLAN_DOMAINS", None)
    base = [sys.executable, "-m", "nowplan.cli", "--import", "house_domain"]
    trace = tmp_path / "t.jsonl"
    run = subprocess.run([*base, "run", "--domain", "house", "--scenario", "sticky", "--seed", "2",
                          "--failure-prob", "0.1", "--trace", str(trace), "--frames", "4"],
                         capture_output=True, text=True, env=env, timeout=120)
    assert run.returncode == 0, run.stderr
    assert "outcome: reached" in run.stdout
    assert '"event": "frame"' in trace.read_text()


def test_the_tutorial_shows_the_example_files_as_they_are() -> None:
    """docs/writing-a-domain.md quotes each file of the example whole; they must not drift apart."""
    import re

    doc = (EXAMPLE.parents[1] / "docs" / "writing-a-domain.md").read_text()
    quoted = re.findall(r"File `examples/house/([\w/.]+)`:\n\n```\w+\n(.*?)\n```\n", doc, flags=re.S)
    assert {name for name, _ in quoted} == {
        "pyproject.toml", "house_domain/__init__.py", "house_domain/model.py", "house_domain/world.py",
        "house_domain/scenarios.py", "house_domain/render.py",
    }
    for name, text in quoted:
        assert text == (EXAMPLE / name).read_text().rstrip("\n"), f"the tutorial's copy of {name} is stale"


def test_pip_installing_the_example_registers_its_entry_point(tmp_path: Path) -> None:
    """A real install (a wheel built by pip into a target directory) is found through its entry point."""
    pytest.importorskip("setuptools", reason="building the example's wheel offline needs setuptools")
    target, source = tmp_path / "site", tmp_path / "house"
    shutil.copytree(EXAMPLE, source, ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
    build = subprocess.run(
        [sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--no-build-isolation",
         "--no-index", "--target", str(target), str(source)],
        capture_output=True, text=True, timeout=300,
    )
    if build.returncode != 0:
        pytest.skip(f"pip could not build the example offline: {build.stderr.strip().splitlines()[-1:]}")
    assert (target / "house_domain" / "model.py").exists()
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(target), *sys.path])}
    env.pop("NOWPLAN_DOMAINS", None)
    listed = subprocess.run([sys.executable, "-m", "nowplan.cli", "domains"], capture_output=True, text=True,
                            env=env, timeout=120)
    assert listed.returncode == 0, listed.stderr
    assert "from entry point house = house_domain:SPEC" in listed.stdout
