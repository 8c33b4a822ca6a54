"""Domains as plugins: entry points, NOWPLAN_DOMAINS and --import find a domain outside src/."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from nowplan.domains import registry

PLUGIN = textwrap.dedent('''
    """A user's domain package outside nowplan's source tree (it reuses logistics' model)."""
    from nowplan.domains.logistics.scenarios import episode
    from nowplan.domains.registry import DomainSpec

    SPEC = DomainSpec(
        name="courier",
        description="a courier domain written outside nowplan",
        scenarios={"one": lambda seed: episode("tiny", seed)},
        default_scenario="one",
    )
''')


@pytest.fixture()
def plugin_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    (tmp_path / "courier_domain.py").write_text(PLUGIN)
    (tmp_path / "not_a_domain.py").write_text("X = 1\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    # a fresh discovery for this test, the registry restored afterwards
    monkeypatch.setattr(registry, "_REGISTRY", {})
    monkeypatch.setattr(registry, "_DISCOVERED", False)
    return tmp_path


def test_nowplan_domains_variable_adds_a_module(plugin_dir: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("NOWPLAN_DOMAINS", "courier_domain")
    names = registry.domain_names()
    assert "courier" in names and "logistics" in names  # the built-in ones are plugins too
    spec = registry.get_domain("courier")
    assert spec.source == "module courier_domain"
    assert registry.get_domain("logistics").source.startswith("entry point logistics")


@pytest.mark.parametrize(("module", "message"), [
    ("no_such_module_here", "cannot import domain module 'no_such_module_here'"),
    ("not_a_domain", "has no SPEC"),
])
def test_a_bad_plugin_module_is_named_with_the_fix(plugin_dir: Path, monkeypatch: pytest.MonkeyPatch,
                                                    module: str, message: str) -> None:
    from nowplan.errors import ScenarioError

    monkeypatch.setenv("NOWPLAN_DOMAINS", module)
    with pytest.raises(ScenarioError, match=message):
        registry.domain_names()


def test_the_cli_runs_a_plugin_domain_with_import(plugin_dir: Path) -> None:
    env = {"PYTHONPATH": f"{plugin_dir}{':' + sys.path[0] if sys.path else ''}", "PATH": "/usr/bin:/bin"}
    run = subprocess.run(
        [sys.executable, "-m", "nowplan.cli", "--import", "courier_domain", "run", "--domain", "courier",
         "--strategy", "hpn", "--seed", "1"],
        capture_output=True, text=True, env=env, timeout=120,
    )
    assert run.returncode == 0, run.stderr
    assert "reached" in run.stdout
    listed = subprocess.run([sys.executable, "-m", "nowplan.cli", "--import", "courier_domain", "domains"],
                            capture_output=True, text=True, env=env, timeout=120)
    assert listed.returncode == 0 and "courier: a courier domain written outside nowplan" in listed.stdout
    bad = subprocess.run([sys.executable, "-m", "nowplan.cli", "--import", "nope_mod", "domains"],
                         capture_output=True, text=True, env=env, timeout=120)
    assert bad.returncode == 2 and "cannot import domain module 'nope_mod'" in bad.stderr
    assert "Traceback" not in bad.stderr
