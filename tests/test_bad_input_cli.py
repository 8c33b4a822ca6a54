"""Issue 14's bad-input list, end to end through the CLI as a user types it: one line on stderr naming
the place and the fix, exit 2, no traceback (the cases tests/test_bad_input.py does not run)."""

from __future__ import annotations

import json
import sqlite3
from pathlib import Path

import pytest

from nowplan.cli import main


def _err(capsys: pytest.CaptureFixture[str], *argv: str) -> str:
    assert main(list(argv)) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1, err
    return err


@pytest.mark.parametrize(("switches", "pair"), [
    ("aggressive+selective", "'aggressive' and 'selective'"),
    ("hpn+monitor-cost+monitor-goal", "'monitor-cost' and 'monitor-goal'"),
    ("online+aggressive", "'online' and 'aggressive'"),
])
def test_contradictory_switches_on_run(switches: str, pair: str, capsys: pytest.CaptureFixture[str]) -> None:
    err = _err(capsys, "run", "--domain", "logistics", "--scenario", "tiny", "--strategy", switches)
    assert pair in err and "contradict" in err and "keep one" in err


def test_contradictory_switches_on_sweep(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = tmp_path / "runs.sqlite"
    err = _err(capsys, "sweep", "--domain", "logistics", "--scenario", "tiny", "--strategies", "hpn,flat+hpn",
               "--seeds", "0", "--store", str(store), "--no-progress")
    assert "contradict" in err and "keep one" in err


def test_a_binary_namo_scenario_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    f = tmp_path / "map.json"
    f.write_bytes(bytes(range(256)) * 4)
    err = _err(capsys, "run", "--domain", "namo", "--scenario", str(f))
    assert "map.json" in err and "UTF-8" in err and "JSON scenario file" in err


def test_a_namo_probability_above_one(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    f = tmp_path / "mine.json"
    f.write_text(json.dumps({"name": "mine", "size": [8, 4], "start": [0.6, 1.5], "goal": [7.4, 1.5],
                             "noise": {"move_fail": 1.5}}))
    err = _err(capsys, "run", "--domain", "namo", "--scenario", str(f))
    assert "noise.move_fail" in err and "[0, 1]" in err


def test_a_fault_level_out_of_range_on_sweep(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    err = _err(capsys, "sweep", "--domain", "namo", "--scenario", "domain1?failure=1.5", "--strategies", "hpn",
               "--seeds", "0", "--store", str(tmp_path / "runs.sqlite"), "--no-progress")
    assert "failure=1.5" in err and "give a probability in [0, 1]" in err


@pytest.mark.parametrize("command", ["sweep", "report"])
def test_a_sqlite_file_that_is_not_a_store(command: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    other = tmp_path / "other.sqlite"
    with sqlite3.connect(other) as db:
        db.execute("CREATE TABLE meta (name TEXT, value TEXT)")
        db.execute("INSERT INTO meta VALUES ('application', 'something else')")
    argv = (["report", str(other), "-o", str(tmp_path / "rep")] if command == "report" else
            ["sweep", "--domain", "logistics", "--scenario", "tiny", "--strategies", "hpn", "--seeds", "0",
             "--store", str(other), "--no-progress"])
    err = _err(capsys, *argv)
    assert "other.sqlite" in err and "not a nowplan run store" in err and "new --store file" in err
