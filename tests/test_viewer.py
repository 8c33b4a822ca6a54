"""The trace viewer without a browser: parsing, line-numbered errors, the model, escaping."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from nowplan.cli import main as cli_main
from nowplan.errors import TraceError
from nowplan.viz.viewer import build_model, read_trace, render_page, write_viewer

DATA = Path(__file__).parent / "data"
LOGISTICS = DATA / "trace_logistics_small_failures.jsonl"
TOY = DATA / "trace_toy_frames.jsonl"


@pytest.mark.parametrize(
    ("lines", "message"),
    [
        (['{"seq": 0, "event": "run_start"}', '{"seq": 1, "event": '], r":2: malformed trace line: Expecting value"),
        (['{"seq": 0, "event": "note", "text": "x"}', "", "[1, 2]"], r":3: malformed trace line: expected a JSON object"),
        (['{"seq": 0, "text": "x"}'], r":1: malformed trace line: no 'event' field"),
        (['{"event": "note"}', '{"event": "plan", "plan_id": "3", "steps": []}'],
         r":2: malformed 'plan' event: field 'plan_id' should be int"),
        (['{"event": "plan", "plan_id": 1, "steps": []}', '{"event": "plan", "plan_id": 1, "steps": []}'],
         r":2: plan 1 was already made on line 1"),
        (['{"event": "plan", "plan_id": 1, "steps": [{"action": null}]}'], r":1: malformed 'plan' event: each step"),
        ([], r"empty trace"),
    ],
)
def test_malformed_traces_name_the_line(tmp_path: Path, lines: list[str], message: str) -> None:
    p = tmp_path / "t.jsonl"
    p.write_text("\n".join(lines) + "\n")
    with pytest.raises(TraceError, match=message):
        read_trace(p)


def test_cli_view_errors_are_one_line(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    p = tmp_path / "bad.jsonl"
    p.write_text('{"event": "run_start"}\nnot json\n')
    assert cli_main(["view", str(p), "-o", str(tmp_path / "x.html")]) == 2
    err = capsys.readouterr().err
    assert "bad.jsonl:2: malformed trace line" in err and "Traceback" not in err
    assert cli_main(["view", str(tmp_path / "missing.jsonl")]) == 2
    assert "no such trace file" in capsys.readouterr().err


def test_model_of_the_logistics_trace() -> None:
    m = build_model(read_trace(LOGISTICS))
    plans = {p["id"]: p for p in m["plans"]}
    assert len(plans) == 23 and m["roots"] == [1, 7, 10, 19]
    p4 = plans[4]
    assert p4["parent"] == 3 and p4["parent_step"] == 1
    assert p4["steps"][1]["action"] == "(drive_truck truck1 c1-l2 c1-l0 c1)"
    assert p4["steps"][1]["primitive"] and p4["steps"][1]["executed"]
    assert plans[3]["steps"][1]["children"] == [4] and plans[3]["steps"][1]["refined"]
    assert plans[1]["pop"]["reason"] == "not applicable"
    assert not plans[1]["steps"][3]["selected"]  # never reached
    failed_steps = [(p["id"], s["index"]) for p in m["plans"] for s in p["steps"] if s["failures"]]
    assert len(failed_steps) == 3
    assert len(m["root_replans"]) == 3 and all(r["trigger"] == "failure" for r in m["root_replans"])
    assert m["root_pop"]["reason"] == "done" and m["end"]["outcome"] == "reached"


def test_page_is_self_contained_and_escapes_trace_strings(tmp_path: Path) -> None:
    out = write_viewer(TOY, tmp_path / "toy.html")
    page = out.read_text()
    # the only <script> elements are ours: the JSON data and the viewer script
    assert page.count("<script") == 2 and page.count("</script>") == 2
    assert "<img src=x" not in page and "window.__pwned=2</script>" not in page
    assert "Content-Security-Policy" in page and "default-src 'none'" in page
    assert not re.search(r"(src|href)\s*=\s*[\"']?(https?:)?//", page)
    data = json.loads(re.search(r'<script type="application/json" id="trace-data">(.*?)</script>',
                                page, re.DOTALL).group(1))  # type: ignore[union-attr]
    frames = data["frames"]
    assert [f["src"] is not None for f in frames] == [True, True, False]  # data URI, file inlined, remote not
    assert frames[1]["src"].startswith("data:image/png;base64,")
    assert "network" in frames[2]["missing"]
    assert data["plans"][1]["steps"][2]["failed_plans"] == []  # plan_failed hangs under plan 1 step 1
    assert data["plans"][0]["steps"][1]["failed_plans"][0]["status"] == "node_limit"
    assert render_page(data).count("<script") == 2


def test_cli_view_default_output(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    trace = tmp_path / "run.jsonl"
    trace.write_text(LOGISTICS.read_text())
    assert cli_main(["view", str(trace)]) == 0
    assert (tmp_path / "run.html").exists() and "run.html" in capsys.readouterr().out
