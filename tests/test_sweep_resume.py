"""A sweep killed with SIGKILL part-way resumes with exactly one record per configuration."""

from __future__ import annotations

import os
import signal
import sqlite3
import subprocess
import sys
import time
from pathlib import Path

from nowplan.experiments.store import Store
from nowplan.experiments.sweep import SweepSpec, parse_seeds

STRATEGIES = "hpn,hpn+aggressive"
SEEDS = "0-9"  # 2 strategies x 10 seeds = 20 runs of the small logistics scenario


def _sweep_cmd(store: Path) -> list[str]:
    return [
        sys.executable, "-m", "nowplan.cli", "sweep", "--domain", "logistics", "--scenario", "small",
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


def test_sigkill_mid_sweep_then_resume(tmp_path: Path) -> None:
    store = tmp_path / "runs.sqlite"
    spec = SweepSpec("logistics", ("small",), tuple(STRATEGIES.split(",")), tuple(parse_seeds(SEEDS)), 60.0)
    expected = {c.key for c in spec.configs()}
    assert len(expected) == 20

    proc = subprocess.Popen(_sweep_cmd(store), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 60
        while _count(store) < 4:
            assert proc.poll() is None, "the sweep ended before it could be killed"
            assert time.monotonic() < deadline, "the sweep stored nothing within 60 s"
            time.sleep(0.01)
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait(timeout=30)
    assert proc.returncode == -signal.SIGKILL
    time.sleep(0.2)  # the workers die with their parent (PR_SET_PDEATHSIG)

    db = sqlite3.connect(store)
    assert db.execute("PRAGMA integrity_check").fetchone()[0] == "ok"
    db.close()
    with Store(store) as st:
        before = {r.key: r.to_dict() for r in st.records()}
    assert 4 <= len(before) < 20, f"kill landed after {len(before)} of 20 runs"
    assert set(before) <= expected

    done = subprocess.run(_sweep_cmd(store) + ["--no-progress"], capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert f"20/20 runs stored ({len(before)} already there, {20 - len(before)} run now" in done.stdout

    db = sqlite3.connect(store)
    rows = db.execute("SELECT key, COUNT(*) FROM runs GROUP BY key").fetchall()
    db.close()
    assert len(rows) == 20 and all(n == 1 for _, n in rows)
    with Store(store) as st:
        after = {r.key: r.to_dict() for r in st.records()}
    assert set(after) == expected  # none lost, none extra
    assert all(after[k] == v for k, v in before.items())  # runs finished before the kill were not redone
    assert all(r["status"] == "done" for r in after.values())
