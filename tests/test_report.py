"""Reports from a stored sweep: tables with mean ± standard error, plots, self-contained HTML."""

from __future__ import annotations

import base64
import math
import re
from pathlib import Path

import pytest

from nowplan.cli import main as cli_main
from nowplan.errors import StoreError
from nowplan.experiments.records import RunConfig, RunRecord, RunStatus, crashed
from nowplan.experiments.report import build_report, render_html, report_store
from nowplan.experiments.runner import LocalBackend
from nowplan.experiments.stats import estimate, group_records, seeds_text
from nowplan.experiments.store import Store
from nowplan.experiments.sweep import SweepSpec, run_sweep


def test_estimate_mean_and_standard_error() -> None:
    e = estimate([1.0, 2.0, 3.0, 4.0])
    assert e.n == 4 and e.mean == 2.5
    assert math.isclose(e.se, math.sqrt((1.5**2 * 2 + 0.5**2 * 2) / 3) / 2)
    assert e.fmt() == "2.5 ± 0.65"
    assert estimate([5.0]).fmt() == "5" and estimate([]).fmt() == "–"
    assert seeds_text([0, 1, 2, 5, 7, 8]) == "0-2,5,7-8"


def _rec(strategy: str, seed: int, actions: int, outcome: str = "reached") -> RunRecord:
    cfg = RunConfig("logistics", "small", strategy, seed, 60.0)
    m = {"outcome": outcome, "reason": "", "actions": actions, "action_counts": {"drive_truck": actions},
         "execution_cost": float(actions), "planning_cpu_s": 0.1, "plans_made": 2, "replans": 0,
         "plan_failures": 0, "wall_s": 0.2}
    return RunRecord(cfg, RunStatus.DONE, outcome, metrics=m, wall_s=0.2)


def test_report_tables_from_known_records(tmp_path: Path) -> None:
    records = [_rec("hpn", 0, 10), _rec("hpn", 1, 12), _rec("hpn", 2, 14, "failed"),
               _rec("flat", 0, 9), crashed(RunConfig("logistics", "small", "flat", 1, 60.0), "Traceback…", "boom <b>")]
    groups = group_records(records)
    assert [g.key[2] for g in groups] == ["flat", "hpn"]
    blocks = build_report(records, "Known <report>", "test")
    md_tables = [b for b in blocks if type(b).__name__ == "Table"]
    outcomes, metrics = md_tables[0], md_tables[1]
    assert ("logistics", "small", "hpn", "3", "2", "1", "0", "0", "0", "0-2") in outcomes.rows
    assert ("logistics", "small", "flat", "2", "1", "0", "0", "0", "1", "0-1") in outcomes.rows
    hpn = next(r for r in metrics.rows if r[2] == "hpn")
    assert hpn[3] == "3" and hpn[4] == "12 ± 1.2"  # actions 10, 12, 14: sd 2, se 2/sqrt(3)
    page = render_html(blocks)
    assert "Known &lt;report&gt;" in page and "boom &lt;b&gt;" in page and "<b>" not in page


def test_report_on_a_stored_sweep(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    store = tmp_path / "runs.sqlite"
    spec = SweepSpec("logistics", ("small",), ("hpn", "hpn+aggressive"), (0, 1, 2), 60.0)
    with Store(store) as st:
        run_sweep(spec, st, LocalBackend(jobs=2), progress=False)
    out = tmp_path / "report"
    assert cli_main(["report", str(store), "-o", str(out)]) == 0
    assert "report.html" in capsys.readouterr().out
    md = (out / "report.md").read_text()
    assert "| logistics | small | hpn | 3 | 3 | 0 | 0 | 0 | 0 | 0-2 |" in md
    assert "| logistics | small | hpn+aggressive | 3 |" in md
    assert re.search(r"\| logistics \| small \| hpn \| 3 \| [\d.]+ ± [\d.]+ \|", md)
    assert "![" in md and (out / "logistics-small.png").read_bytes().startswith(b"\x89PNG")
    page = (out / "report.html").read_text()
    imgs = re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', page)
    assert len(imgs) == 1 and base64.b64decode(imgs[0]).startswith(b"\x89PNG")
    assert not re.search(r"(src|href)=\"(?!data:)", page)  # nothing to fetch: self-contained
    files = report_store(store, tmp_path / "again", title="Again")
    assert files.html.exists() and "Again" in files.markdown.read_text()


def test_report_errors(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    Store(tmp_path / "empty.sqlite").close()
    with pytest.raises(StoreError, match="holds no runs"):
        report_store(tmp_path / "empty.sqlite", tmp_path / "out")
    assert cli_main(["report", str(tmp_path / "missing.sqlite"), "-o", str(tmp_path / "o")]) == 2
    assert "no such run store" in capsys.readouterr().err
