"""The plan library (SQLite): round trips, reuse across runs, and clear errors for damaged files."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest

import nowplan.domains.pieces  # noqa: F401  (registers the pieces domain's monitor support)
from nowplan.acting.hpn import Executive
from nowplan.acting.monitor import Monitor, MonitorConfig, monitor_settings
from nowplan.acting.monitor_support import simulate
from nowplan.acting.plan_library import PlanLibrary, goal_key, state_key
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.cli import main as cli_main
from nowplan.domains.pieces.meansends import plan_means_ends
from nowplan.domains.pieces.model import DOMAIN
from nowplan.domains.pieces.scenarios import Size, generate
from nowplan.errors import StoreError
from nowplan.worlds.symbolic import SymbolicWorld


def _stored(lib: PlanLibrary, seed: int = 0):
    t = generate(Size(6, 6, 6), seed)
    p = t.core()
    plan = plan_means_ends(DOMAIN, p.objects, p.init, p.goal).plan
    states = simulate(DOMAIN, p.init, plan.actions)
    pid = lib.add(DOMAIN.name, p.init, p.goal, plan.actions, states)
    return p, plan, states, pid


def test_round_trip_and_reopen(tmp_path: Path) -> None:
    path = tmp_path / "lib.sqlite"
    with PlanLibrary(path) as lib:
        p, plan, states, pid = _stored(lib)
        assert lib.add(DOMAIN.name, p.init, p.goal, plan.actions, states) == pid  # stored once
        _stored(lib, seed=1)
        assert len(lib) == 2
    with PlanLibrary(path) as lib:  # persisted
        [sp] = lib.lookup(DOMAIN.name, p.init, p.goal)
        assert sp.id == pid and sp.rebuild(DOMAIN) == list(plan.actions)
        assert list(sp.states) == states and sp.state_keys[0] == state_key(p.init)
        assert sp.cost == pytest.approx(plan.cost()) and sp.goal_key == goal_key(p.goal)
        assert [x.id for x in lib.toward(DOMAIN.name, p.goal)] == [pid]
        assert lib.lookup("logistics", p.init, p.goal) == []


def test_a_file_that_is_not_a_library_gives_a_clear_error(tmp_path: Path) -> None:
    path = tmp_path / "junk.sqlite"
    path.write_bytes(b"this is not a database, just some bytes " * 100)
    with pytest.raises(StoreError, match=r"junk\.sqlite.*not a nowplan plan library or it is corrupted"):
        PlanLibrary(path)


def test_damaged_rows_and_other_versions_are_store_errors(tmp_path: Path) -> None:
    path = tmp_path / "lib.sqlite"
    with PlanLibrary(path) as lib:
        p, *_ = _stored(lib)
    db = sqlite3.connect(path)
    db.execute("DELETE FROM states WHERE idx = 1")
    db.commit()
    db.close()
    with PlanLibrary(path) as lib, pytest.raises(StoreError, match="damaged"):
        lib.toward(DOMAIN.name, p.goal)
    db = sqlite3.connect(path)
    db.execute("UPDATE plans SET actions = ?", ('[["move_piece"',))  # truncated JSON
    db.commit()
    db.close()
    with PlanLibrary(path) as lib, pytest.raises(StoreError, match="cannot be read"):
        lib.toward(DOMAIN.name, p.goal)
    db = sqlite3.connect(path)
    db.execute("UPDATE meta SET value = '99' WHERE key = 'schema_version'")
    db.commit()
    db.close()
    with pytest.raises(StoreError, match="schema version 99"):
        PlanLibrary(path)


def test_unknown_operators_are_refused_on_rebuild(tmp_path: Path) -> None:
    with PlanLibrary(tmp_path / "lib.sqlite") as lib:
        p, *_ = _stored(lib)
        sp = lib.toward(DOMAIN.name, p.goal)[0]
    from nowplan.domains.logistics.model import DOMAIN as LOGISTICS

    with pytest.raises(StoreError, match="does not define"):
        sp.rebuild(LOGISTICS)


def _run(task, config: MonitorConfig) -> Monitor:
    p = task.core()
    world = SymbolicWorld(DOMAIN, p.init)
    with monitor_settings(config):
        ex = Executive(p, world, SymbolicBelief(p.init), parse_strategy("hpn+monitor"), seed=0)
    m = ex.run()
    assert m.outcome.value == "reached" and DOMAIN.satisfies(world.state, p.goal)
    return next(x for x in ex.mechanisms if isinstance(x, Monitor))


def test_a_warm_library_is_reused_across_runs(tmp_path: Path) -> None:
    task = generate(Size(6, 6, 6), 3)
    cfg = MonitorConfig(library_path=str(tmp_path / "lib.sqlite"))
    first = _run(task, cfg)
    assert first.stats.reuses == 0 and first.stats.stored == 1 and first.stats.planning_s > 0
    second = _run(task, cfg)
    assert second.stats.reuses == 1 and second.stats.stored == 0 and second.stats.planning_s == 0
    read_only = _run(task, MonitorConfig(library_path=str(tmp_path / "lib.sqlite"), library_write=False))
    assert read_only.stats.reuses == 1
    with PlanLibrary(tmp_path / "lib.sqlite") as lib:
        assert len(lib) == 1


def test_the_cli_reports_a_corrupted_library_in_one_line(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                                       capsys: pytest.CaptureFixture[str]) -> None:
    bad = tmp_path / "broken.sqlite"
    bad.write_bytes(b"\x00garbage" * 512)
    monkeypatch.setenv("NOWPLAN_PLAN_LIBRARY", str(bad))
    code = cli_main(["run", "--domain", "pieces", "--scenario", "tiny", "--strategy", "hpn+monitor"])
    err = capsys.readouterr().err
    assert code == 2 and "broken.sqlite" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
