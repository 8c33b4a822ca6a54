"""Sweeps: seeds syntax, the run store, crashes, time limits, bad names, summary."""

from __future__ import annotations

import os
import sqlite3
import threading
from collections.abc import Iterator
from pathlib import Path

import pytest

from nowplan.cli import main as cli_main
from nowplan.domains import registry
from nowplan.domains.registry import DomainSpec, Episode
from nowplan.errors import ScenarioError, StoreError
from nowplan.experiments.precheck import check_runs, refusal
from nowplan.experiments.records import RunConfig, RunRecord, RunStatus
from nowplan.experiments.runner import LocalBackend, execute
from nowplan.experiments.store import Store
from nowplan.experiments.sweep import SweepSpec, SweepState, parse_seeds, run_sweep
from tests.helpers import process_alive


def test_parse_seeds() -> None:
    assert parse_seeds("0-9") == list(range(10))
    assert parse_seeds("0,3,5") == [0, 3, 5]
    assert parse_seeds("7") == [7]
    assert parse_seeds("0-2, 10,1") == [0, 1, 2, 10]
    for bad in ("", "a", "3-1", "1-", "-1", "1.5"):
        with pytest.raises(ScenarioError):
            parse_seeds(bad)


def test_config_key_is_stable_and_distinct() -> None:
    a = RunConfig("logistics", "small", "hpn", 3, 60.0)
    assert a.key == RunConfig("logistics", "small", "hpn", 3, 60).key
    others = [
        RunConfig("logistics", "small", "hpn", 4, 60.0),
        RunConfig("logistics", "small", "flat", 3, 60.0),
        RunConfig("logistics", "medium", "hpn", 3, 60.0),
        RunConfig("logistics", "small", "hpn", 3, 30.0),
    ]
    assert len({a.key, *(o.key for o in others)}) == 5


def _record(seed: int, outcome: str = "reached") -> RunRecord:
    cfg = RunConfig("logistics", "small", "hpn", seed, 10.0)
    return RunRecord(cfg, RunStatus.DONE, outcome, metrics={"outcome": outcome, "actions": seed})


def test_store_roundtrip_one_record_per_key(tmp_path: Path) -> None:
    path = tmp_path / "runs.sqlite"
    with Store(path) as st:
        assert st.put(_record(1))
        assert not st.put(_record(1, "failed"))  # first write wins
        assert st.get(_record(1).key).outcome == "reached"  # type: ignore[union-attr]
        assert st.put(_record(1, "failed"), replace=True)
        st.put(_record(2))
        assert len(st) == 2
    with Store(path, create=False) as st:
        recs = st.records()
        assert [r.config.seed for r in recs] == [1, 2]
        assert recs[0].outcome == "failed"
        assert recs[0].to_dict() == RunRecord.from_dict(recs[0].to_dict()).to_dict()


def test_store_incompatible_schema_and_foreign_files(tmp_path: Path) -> None:
    path = tmp_path / "old.sqlite"
    Store(path).close()
    db = sqlite3.connect(path)
    db.execute("UPDATE meta SET value = '0' WHERE name = 'schema_version'")
    db.commit()
    db.close()
    with pytest.raises(StoreError, match="incompatible run store.*schema version 0"):
        Store(path)
    other = tmp_path / "other.sqlite"
    db = sqlite3.connect(other)
    db.execute("CREATE TABLE t (x)")
    db.commit()
    db.close()
    with pytest.raises(StoreError, match="not a nowplan run store"):
        Store(other)
    junk = tmp_path / "junk.sqlite"
    junk.write_text("not a database at all " * 100)
    with pytest.raises(StoreError, match="not a usable nowplan run store"):
        Store(junk)
    with pytest.raises(StoreError, match="no such run store"):
        Store(tmp_path / "missing.sqlite", create=False)


# -- a throw-away domain whose scenarios crash or hang (workers are forked, so they see it) --


def _boom(seed: int) -> Episode:
    raise RuntimeError(f"boom {seed}")


def _hang(seed: int) -> Episode:
    # note the worker's pid, then block for good: only the backend's kill ends this run
    Path(os.environ["NOWPLAN_TEST_HANG_DIR"], f"{seed}.pid").write_text(str(os.getpid()))
    threading.Event().wait()
    raise AssertionError("unreachable")


@pytest.fixture()
def broken_domain(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    spec = DomainSpec("broken-test", "scenarios that crash or hang", {"boom": _boom, "hang": _hang})
    monkeypatch.setitem(registry._REGISTRY, spec.name, spec)
    yield spec.name


def test_execute_records_a_crash(broken_domain: str) -> None:
    rec = execute(RunConfig(broken_domain, "boom", "hpn", 4, 10.0))
    assert rec.status is RunStatus.CRASHED and rec.outcome == "error"
    assert rec.reason == "RuntimeError: boom 4"
    assert rec.error is not None and "Traceback" in rec.error


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="reads process states from /proc")
@pytest.mark.timeout(120)  # the hung runs never end by themselves: a backend waiting for them hangs here
def test_sweep_crash_and_timeout_are_recorded_and_the_sweep_goes_on(
    tmp_path: Path, broken_domain: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    hang_dir = tmp_path / "hung"
    hang_dir.mkdir()
    monkeypatch.setenv("NOWPLAN_TEST_HANG_DIR", str(hang_dir))  # the forked workers inherit it
    with Store(tmp_path / "runs.sqlite") as st:
        boom = run_sweep(SweepSpec(broken_domain, ("boom",), ("hpn",), (0, 1, 2), 10.0), st,
                         LocalBackend(jobs=2), progress=False)
        assert boom.state is SweepState.COMPLETE and boom.ran == 3
        assert {r.status for r in boom.records} == {RunStatus.CRASHED}
        hang = run_sweep(SweepSpec(broken_domain, ("hang",), ("hpn",), (0, 1), 0.5), st,
                         LocalBackend(jobs=2, grace=1.5), progress=False)
        assert [r.status for r in hang.records] == [RunStatus.TIMEOUT] * 2
        assert all(r.outcome == "limit" and "(hard limit 2 s)" in r.reason for r in hang.records)
        # both runs reached their scenario, and the backend killed (and reaped) both workers
        pids = [int(f.read_text()) for f in sorted(hang_dir.glob("*.pid"))]
        assert len(pids) == 2 and not any(process_alive(pid) for pid in pids)
        assert len(st) == 5
        # crashed runs are finished runs: a resume skips them unless asked to retry
        again = run_sweep(SweepSpec(broken_domain, ("boom",), ("hpn",), (0, 1, 2), 10.0), st,
                          LocalBackend(jobs=2), progress=False)
        assert again.ran == 0 and again.already == 3
        retry = run_sweep(SweepSpec(broken_domain, ("boom",), ("hpn",), (0, 1, 2), 10.0), st,
                          LocalBackend(jobs=2), progress=False, retry_errors=True)
        assert retry.ran == 3 and len(st) == 5
        assert "crashed runs" in retry.summary() and "RuntimeError: boom 0" in retry.summary()


def test_local_sweep_on_logistics_and_summary(tmp_path: Path) -> None:
    spec = SweepSpec("logistics", ("small",), ("hpn", "hpn+aggressive"), (0, 1), 60.0)
    with Store(tmp_path / "runs.sqlite") as st:
        res = run_sweep(spec, st, LocalBackend(jobs=2), progress=False)
        assert res.state is SweepState.COMPLETE and res.ran == 4 and len(res.records) == 4
        for r in res.records:
            assert r.status is RunStatus.DONE and r.outcome == "reached"
            assert r.metrics["actions"] > 0 and r.metrics["plans_made"] > 0
            assert set(r.metrics["action_counts"]) <= {
                "drive_truck", "fly_airplane", "load_truck", "unload_truck", "load_airplane", "unload_airplane"
            }
            assert r.version and r.wall_s > 0
        # same configuration in-process gives the same decisions (runs are seeded)
        direct = execute(res.records[0].config)
        assert direct.decisions() == res.records[0].decisions()
        text = res.summary()
        assert "4/4 runs stored" in text and "hpn+aggressive" in text


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--domain", "nope"], "unknown domain 'nope'; valid domains: "),
        (["--scenario", "huge"], "unknown scenario 'huge' for domain 'logistics'; valid scenarios:"),
        (["--strategies", "hpn,bogus"], "unknown strategy 'bogus'; valid strategies:"),
        (["--seeds", "9-2"], "seed range '9-2' runs backwards"),
        (["--address", "auto"], "--address is for the Ray backend"),
    ],
)
def test_sweep_cli_bad_input_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], args: list[str], message: str
) -> None:
    base = {"--domain": "logistics", "--scenario": "small", "--strategies": "hpn", "--seeds": "0"}
    for flag, value in zip(args[::2], args[1::2], strict=True):
        base[flag] = value
    argv = ["sweep", "--store", str(tmp_path / "s.sqlite"), "--no-progress"]
    for k, v in base.items():
        argv += [k, v]
    assert cli_main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err and "Traceback" not in err
    assert not (tmp_path / "s.sqlite").exists()


def test_sweep_cli_incompatible_store(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    path = tmp_path / "old.sqlite"
    Store(path).close()
    db = sqlite3.connect(path)
    db.execute("UPDATE meta SET value = '99' WHERE name = 'schema_version'")
    db.commit()
    db.close()
    argv = ["sweep", "--domain", "logistics", "--scenario", "small", "--strategies", "hpn",
            "--seeds", "0", "--store", str(path), "--no-progress"]
    assert cli_main(argv) == 2
    assert "incompatible run store" in capsys.readouterr().err


# -- the pre-check: every (scenario, strategy) built as its run would be, before any run ------------


def test_probes_are_one_configuration_per_scenario_and_strategy_at_the_first_seed() -> None:
    spec = SweepSpec("logistics", ("tiny", "small"), ("hpn", "flat"), (3, 5, 7), 10.0)
    probes = spec.probes()
    assert [(c.scenario, c.strategy, c.seed) for c in probes] == [
        ("tiny", "hpn", 3), ("tiny", "flat", 3), ("small", "hpn", 3), ("small", "flat", 3)]
    later = [c for c in spec.configs() if c.seed > 3]  # a resumed sweep checks what it has left to run
    assert {c.seed for c in spec.probes(later)} == {5}


def test_refusal_names_the_first_refused_run_and_leaves_crashes_to_the_runs(broken_domain: str) -> None:
    ok = RunConfig("logistics", "tiny", "hpn", 0, 10.0)
    assert refusal([ok, RunConfig(broken_domain, "boom", "hpn", 0, 10.0)]) is None  # a crash is not a refusal
    why = refusal([ok, RunConfig("marsupial", "single-2", "flat", 1, 10.0),
                   RunConfig("logistics", "tiny", "domain-planner", 0, 10.0)])
    assert why is not None and why.startswith("marsupial/single-2 flat seed=1: strategy switch 'flat'")


@pytest.mark.timeout(60)
def test_a_pre_check_that_hangs_is_stopped_and_refuses_nothing(
        tmp_path: Path, broken_domain: str, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("NOWPLAN_TEST_HANG_DIR", str(tmp_path))
    check_runs([RunConfig(broken_domain, "hang", "hpn", 4, 10.0)], timeout=1.0)  # returns: no refusal
    pid = int((tmp_path / "4.pid").read_text())  # the worker reached the scenario, and was killed
    assert not process_alive(pid)


def test_run_sweep_refuses_before_storing_anything(tmp_path: Path) -> None:
    spec = SweepSpec("logistics", ("tiny",), ("hpn", "domain-planner"), (0, 1), 10.0)
    with Store(tmp_path / "runs.sqlite") as st:
        with pytest.raises(ScenarioError, match="logistics/tiny domain-planner seed=0: .*no planner of its own"):
            run_sweep(spec, st, LocalBackend(jobs=1), progress=False)
        assert len(st) == 0
