"""nowplan reproduce: registered reproductions run; the others say plainly they have not landed."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.cli import main as cli_main
from nowplan.experiments import reproductions
from nowplan.experiments.papers import PAPERS
from nowplan.experiments.reproductions import (
    Reproduction,
    ReproductionOptions,
    ReproductionResult,
    ReproStatus,
    side_by_side,
)


@pytest.mark.parametrize("seed", ["000", "002", "003", "004"])
def test_every_seed_has_a_reproduction(seed: str) -> None:
    assert seed in reproductions.registered()


@pytest.mark.parametrize("seed", ["000", "004"])
def test_unlanded_reproduction_says_so(seed: str, capsys: pytest.CaptureFixture[str],
                                       monkeypatch: pytest.MonkeyPatch) -> None:
    declared = reproductions.declared()  # the domains' specs declare them; take one away
    monkeypatch.setattr(reproductions, "declared", lambda: {k: v for k, v in declared.items() if k != seed})
    assert cli_main(["reproduce", seed, "--json", "--quick"]) == 3
    captured = capsys.readouterr()
    doc = json.loads(captured.out)
    assert doc["seed"] == seed and doc["status"] == "not_implemented"
    assert doc["rows"] == []  # no fake numbers
    assert doc["notes"].startswith("not yet implemented:")
    assert doc["paper"] == [dict(r) for r in PAPERS[seed].rows]
    assert "not yet implemented" in captured.err and "has not landed" in captured.err


def test_paper_numbers_are_transcribed() -> None:
    bhpn = {(r["domain"], r["algorithm"]): r for r in PAPERS["000"].rows}
    assert bhpn[("Avg", "selective replanning")]["moves"] == 8.1
    assert bhpn[("1", "original BHPN")]["picks_places"] == 4.75
    ss = {(r["task"], r["algorithm"]): r for r in PAPERS["004"].rows}
    assert ss[("Cook", "both")] == {"task": "Cook", "algorithm": "both", "success_pct": 100.0,
                                     "planning_time_s": 203.0, "source": "Table I"}
    assert len(PAPERS["004"].rows) == 16 and PAPERS["003"].rows == ()


def test_unknown_seed(capsys: pytest.CaptureFixture[str]) -> None:
    assert cli_main(["reproduce", "001"]) == 2
    assert "unknown seed '001'; valid seeds: 000, 002, 003, 004" in capsys.readouterr().err


def test_a_registered_reproduction_runs(monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str],
                                        tmp_path: Path) -> None:
    seen: list[ReproductionOptions] = []

    def run(opts: ReproductionOptions) -> ReproductionResult:
        seen.append(opts)
        return ReproductionResult("003", ReproStatus.DONE, rows=[{"task": "t", "steps": 4.0}], notes="toy")

    declared = reproductions.declared()
    monkeypatch.setattr(reproductions, "declared",
                        lambda: {**declared, "003": Reproduction("003", "a toy reproduction", run)})
    assert cli_main(["reproduce", "3", "--quick", "--out", str(tmp_path), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["status"] == "done" and doc["rows"] == [{"task": "t", "steps": 4.0}]
    assert seen == [ReproductionOptions(quick=True, out_dir=tmp_path)]


def test_side_by_side_table() -> None:
    t = side_by_side([{"task": "Cook", "success_pct": 90.0}], [dict(r) for r in PAPERS["004"].rows
                     if r["algorithm"] == "both"], ["task"])
    assert t.header[:3] == ("task", "success_pct (ours)", "success_pct (paper)")
    cook = next(r for r in t.rows if r[0] == "Cook")
    assert cook[1:3] == ("90", "100")


def test_each_seed_comes_from_the_spec_of_the_domain_that_runs_it() -> None:
    from nowplan.domains.registry import get_domain

    owners = {r.seed: name for name in ("namo", "marsupial", "pieces", "kitchen")
              for r in get_domain(name).reproductions}
    assert owners == {"000": "namo", "002": "marsupial", "003": "pieces", "004": "kitchen"}
