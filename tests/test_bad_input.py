"""Bad input gets one line naming the place and the fix, exit 2, never a traceback (issue 14)."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.cli import main

LOG = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "logistics"


def _err(capsys: pytest.CaptureFixture[str], *argv: str) -> str:
    assert main(list(argv)) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    return err


def test_a_binary_criticality_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    crit = tmp_path / "bin.crit"
    crit.write_bytes(bytes(range(256)))
    err = _err(capsys, "plan", str(LOG / "domain.pddl"), str(LOG / "p01.pddl"), "--criticality", str(crit))
    assert "bin.crit" in err and "UTF-8 text" in err


def test_a_trace_path_that_is_a_directory(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    err = _err(capsys, "run", "--domain", "logistics", "--scenario", "tiny", "--trace", str(tmp_path))
    assert "is a directory" in err and "trace.jsonl" in err


def test_plan_level_below_zero(capsys: pytest.CaptureFixture[str]) -> None:
    err = _err(capsys, "plan", str(LOG / "domain.pddl"), str(LOG / "p01.pddl"), "--level", "-1")
    assert "--level -1 is out of range" in err and "'flat'" in err


def test_exogenous_changes_on_a_world_without_any(capsys: pytest.CaptureFixture[str]) -> None:
    err = _err(capsys, "run", str(LOG / "domain.pddl"), str(LOG / "p01.pddl"), "--exogenous-prob", "0.5")
    assert "--exogenous-prob" in err and "drop it" in err


def test_contradictory_strategy_on_the_command_line(capsys: pytest.CaptureFixture[str]) -> None:
    err = _err(capsys, "run", "--domain", "logistics", "--scenario", "tiny", "--strategy", "flat+hpn")
    assert "contradict" in err


def test_a_sweep_with_a_refused_strategy_is_refused_before_it_runs(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the domain declares 'flat' unsupported: checked on a built episode before any run, nothing stored
    err = _err(capsys, "sweep", "--domain", "marsupial", "--scenario", "single-2", "--strategies", "hpn,flat",
               "--seeds", "0", "--store", str(tmp_path / "runs.sqlite"), "--no-progress")
    assert "marsupial/single-2 flat seed=0" in err and "does not apply to domain marsupial" in err
    assert "choose another strategy" in err
    assert not (tmp_path / "runs.sqlite").exists()


def test_a_monitor_refusal_is_found_before_the_sweep_runs(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    # the monitor refuses NAMO's belief (not a point state) when the executive is built
    # (Mechanism.check), so the sweep's pre-check finds it: one line, exit 2, nothing stored
    store = tmp_path / "runs.sqlite"
    err = _err(capsys, "sweep", "--domain", "namo", "--scenario", "simple", "--strategies", "hpn+monitor",
               "--seeds", "0-1", "--store", str(store), "--no-progress", "--jobs", "1")
    assert "not a point state" in err and "drop the monitor switch" in err
    assert not store.exists()


def test_an_action_defined_twice(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    grip = LOG.parent / "gripper"
    text = (grip / "domain.pddl").read_text()
    first = text.index("(:action")
    second = text.index("(:action", first + 1)
    dup = tmp_path / "dup.pddl"
    dup.write_text(text[:second] + text[first:second] + text[second:])
    err = _err(capsys, "plan", str(dup), str(grip / "p01.pddl"))
    assert "defined twice" in err and "dup.pddl" in err


def test_a_store_damaged_in_its_middle_pages(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = tmp_path / "runs.sqlite"
    assert main(["sweep", "--domain", "logistics", "--scenario", "tiny", "--strategies", "hpn,flat",
                 "--seeds", "0-9", "--store", str(store), "--no-progress"]) == 0
    capsys.readouterr()
    data = bytearray(store.read_bytes())
    page = 4096
    assert len(data) >= 5 * page
    for i in range(3 * page, 4 * page):  # a data page, not the schema's
        data[i] = (i * 37) % 256
    store.write_bytes(bytes(data))
    for argv in (["report", str(store), "-o", str(tmp_path / "rep")],
                 ["sweep", "--domain", "logistics", "--scenario", "tiny", "--strategies", "hpn",
                  "--seeds", "0-11", "--store", str(store), "--no-progress"]):
        err = _err(capsys, *argv)
        assert "runs.sqlite" in err and ("damaged" in err or "malformed" in err)
