"""A sweep killed with SIGKILL part-way resumes with exactly one record per configuration.

The sweep runs the logistics ``small`` scenario through tests/gated_sweep.py, whose runs of
seeds >= 2 wait while a gate file exists: with two workers, the first four configurations
(seeds 0 and 1, both strategies) finish and the next two hang at the gate, so the kill
always lands after exactly four stored runs, whatever the machine's speed.  Every run logs
its start, so the test counts executions: a resumed sweep must not run a stored
configuration again.
"""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import pytest

from nowplan.experiments.store import Store
from nowplan.experiments.sweep import SweepSpec, parse_seeds
from tests.helpers import process_alive

STRATEGIES = "hpn,hpn+aggressive"
SEEDS = "0-9"  # 2 strategies x 10 seeds = 20 runs of the small logistics scenario
GATE_FROM = 2  # runs of seeds 0 and 1 (the first four configurations) pass; the rest wait
HELPER = Path(__file__).with_name("gated_sweep.py")


def _sweep_cmd(store: Path) -> list[str]:
    return [
        sys.executable, str(HELPER), "sweep", "--domain", "logistics-gated", "--scenario", "small",
        "--strategies", STRATEGIES, "--seeds", SEEDS, "--store", str(store), "--jobs", "2",
        "--time-limit", "60",
    ]


def _count(store: Path) -> int:
    if not store.exists():
        return 0
    try:
        db = sqlite3.connect(f"file:{store}?mode=ro", uri=True, timeout=1.0)
        try:
            return int(db.execute("SELECT COUNT(*) FROM runs").fetchone()[0])
        finally:
            db.close()
    except sqlite3.Error:  # not created yet, or locked for a moment
        return 0


def _starts(runlog: Path, kind: str = "run") -> list[tuple[int, int]]:
    """(seed, worker pid) of every run started so far (``kind="check"``: every scenario the sweep's
    pre-check built)."""
    if not runlog.exists():
        return []
    complete = runlog.read_text().split("\n")[:-1]  # a line being written has no newline yet
    return [(int(s), int(p)) for s, p, k in (line.split() for line in complete) if k == kind]


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="workers die with the sweep via PR_SET_PDEATHSIG")
@pytest.mark.timeout(240)  # the waits below have no clock of their own
def test_sigkill_mid_sweep_then_resume(tmp_path: Path) -> None:
    store, gate, runlog = tmp_path / "runs.sqlite", tmp_path / "gate", tmp_path / "runs.log"
    gate.touch()
    env = {**os.environ, "NOWPLAN_TEST_GATE": str(gate), "NOWPLAN_TEST_RUNLOG": str(runlog),
           "NOWPLAN_TEST_GATE_FROM": str(GATE_FROM)}
    spec = SweepSpec("logistics-gated", ("small",), tuple(STRATEGIES.split(",")), tuple(parse_seeds(SEEDS)), 60.0)
    configs = spec.configs()
    expected = {c.key for c in configs}
    assert len(expected) == 20
    first = {c.key for c in configs if c.seed < GATE_FROM}
    assert {c.key for c in configs[:4]} == first  # the first four dispatched (seeds outermost)

    err = tmp_path / "sweep.err"
    with err.open("w") as fh:
        proc = subprocess.Popen(_sweep_cmd(store), stdout=subprocess.DEVNULL, stderr=fh,
                                start_new_session=True, env=env)
    try:
        # both workers are held at the gate: the four runs before them are stored, no more can be
        while not (_count(store) >= 4 and sum(s >= GATE_FROM for s, _ in _starts(runlog)) == 2):
            assert proc.poll() is None, f"the sweep ended before it could be killed: {err.read_text()}"
            time.sleep(0.02)
        held = [pid for s, pid in _starts(runlog) if s >= GATE_FROM]
        assert all(process_alive(pid) for pid in held)
        os.kill(proc.pid, signal.SIGKILL)  # the sweep only: its workers must die with it
        proc.wait()
    finally:
        if proc.poll() is None:  # a failed check above: stop the whole session
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    assert proc.returncode == -signal.SIGKILL
    while any(process_alive(pid) for pid in held):  # PR_SET_PDEATHSIG; the test's time-out bounds this
        time.sleep(0.02)

    db = sqlite3.connect(store)
    assert db.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    db.close()
    with Store(store) as st:
        before = {r.key: r.to_dict() for r in st.records()}
    assert set(before) == first  # exactly the runs that could finish
    assert Counter(s for s, _ in _starts(runlog)) == {0: 2, 1: 2, 2: 2}
    # before any run, the pre-check built the scenario once (the first seed's) and ran nothing
    assert [s for s, _ in _starts(runlog, "check")] == [0]

    gate.unlink()
    done = subprocess.run(_sweep_cmd(store) + ["--no-progress"], capture_output=True, text=True,
                          check=False, env=env)
    assert done.returncode == 0, done.stderr
    assert "20/20 runs stored (4 already there, 16 run now" in done.stdout

    # each stored configuration ran once; the two killed at the gate ran again, once
    assert Counter(s for s, _ in _starts(runlog)) == {0: 2, 1: 2, 2: 4, **{s: 2 for s in range(3, 10)}}
    assert [s for s, _ in _starts(runlog, "check")] == [0, 0]  # the resumed sweep checked again
    db = sqlite3.connect(store)
    rows = db.execute("SELECT key, COUNT(*) FROM runs GROUP BY key").fetchall()
    db.close()
    assert len(rows) == 20 and all(n == 1 for _, n in rows)
    with Store(store) as st:
        after = {r.key: r.to_dict() for r in st.records()}
    assert set(after) == expected  # none lost, none extra
    assert all(after[k] == v for k, v in before.items())  # the stored records were kept as they were
    assert all(r["status"] == "done" and r["outcome"] == "reached" for r in after.values())
