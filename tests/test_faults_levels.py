"""benchmarks/faults.py --levels: fault levels as in the table's faults column."""

from __future__ import annotations

import pytest

from benchmarks.faults import main, parse_levels
from nowplan.errors import ScenarioError
from nowplan.experiments.faults import Faults


def test_levels_as_in_the_table() -> None:
    assert parse_levels("none, exogenous=0.5,failure=0.5&exogenous=0.5") == (
        Faults(), Faults(exogenous=0.5), Faults(failure=0.5, exogenous=0.5))


def test_a_bad_level_is_refused() -> None:
    with pytest.raises(ScenarioError):
        parse_levels("failur=0.5")


def test_a_bad_level_is_one_line_and_exit_2(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["--levels", "failure=2", "--summarize", "--store", "/nonexistent/x.sqlite"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "--levels" in err and "out of range" in err
