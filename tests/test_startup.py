"""What ``nowplan run`` and ``nowplan plan`` import at start-up (the issue-18 whole-process CPU).

A plain ``--strategy hpn`` run imports neither the mechanism modules of switches it does not name
(the monitor's plan library with sqlite3, RCHPN's reordering, the online policy), nor
``importlib.metadata`` (the version is a constant), nor the regression search when every call searches
forward.  Checked in a fresh interpreter by the modules it has loaded, not by timing.
"""

from __future__ import annotations

import importlib
import importlib.metadata
import json
import subprocess
import sys
from pathlib import Path

import nowplan
from nowplan.acting.mechanisms import SWITCHES
from nowplan.acting.strategy import MECHANISM_MODULES, parse_strategy, strategy_names

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
LAZY = ("importlib.metadata", "nowplan.acting.online", "nowplan.acting.monitor", "nowplan.acting.peephole",
        "nowplan.acting.plan_library", "sqlite3", "nowplan.planning.regression_search")


def loaded_after(argv: list[str]) -> set[str]:
    """The modules a fresh interpreter holds after ``nowplan ARGV`` (its output discarded)."""
    code = ("import contextlib, io, json, sys\nfrom nowplan.cli import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n    main(sys.argv[1:])\n"
            "print(json.dumps(sorted(sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True, timeout=120, check=True)
    return set(json.loads(out.stdout.splitlines()[-1]))


def test_an_auto_hpn_run_and_flat_planning_load_none_of_the_unused_modules() -> None:
    d = CLASSICAL / "logistics"
    pair = [str(d / "domain.pddl"), str(d / "p01.pddl")]
    run = loaded_after(["run", *pair, "--criticality", "auto", "--strategy", "hpn", "--json"])
    assert "nowplan.acting.hpn" in run and "nowplan.acting.refine_flat" in run  # it did run
    assert not run & set(LAZY), sorted(run & set(LAZY))
    plan = loaded_after(["plan", *pair, "--json", "--improve", "0"])
    assert "nowplan.planning.forward" in plan
    assert not plan & set(LAZY), sorted(plan & set(LAZY))


def test_a_named_switch_loads_its_module() -> None:
    s = parse_strategy("hpn+monitor")
    assert [m.name for m in s.mechanisms()]  # the monitor's mechanism, from the module it loaded
    assert "nowplan.acting.monitor" in sys.modules


def test_the_static_switch_names_are_what_the_modules_register() -> None:
    """Each mechanism module, imported in turn in a fresh interpreter, registers exactly the switches
    ``MECHANISM_MODULES`` names for it (so a strategy naming one imports the module that defines it)."""
    code = ("import importlib, json\nfrom nowplan.acting.mechanisms import SWITCHES\n"
            "from nowplan.acting.strategy import MECHANISM_MODULES\nout = {}\n"
            "for m in MECHANISM_MODULES:\n    before = set(SWITCHES)\n    importlib.import_module(m)\n"
            "    out[m] = sorted(set(SWITCHES) - before)\nprint(json.dumps(out))")
    got = json.loads(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                                    check=True).stdout)
    assert got == {m: sorted(names) for m, names in MECHANISM_MODULES.items()}
    importlib.import_module("nowplan.acting.monitor")  # (any one: the names need no import)
    assert strategy_names() == sorted({*SWITCHES, *(n for names in MECHANISM_MODULES.values() for n in names)})
    for module in MECHANISM_MODULES:
        importlib.import_module(module)
    assert strategy_names() == sorted(SWITCHES)


def test_the_version_constant_is_the_installed_distributions() -> None:
    assert nowplan.__version__ == importlib.metadata.version("nowplan")
