"""Lazy trace fields (trace.py): made when the events are read or written, never lost."""

from __future__ import annotations

import json
from pathlib import Path

from nowplan.trace import Lazy, Trace


def test_lazy_fields_are_made_when_the_events_are_read() -> None:
    calls: list[int] = []

    def make() -> list[str]:
        calls.append(1)
        return ["at(a, p)"]

    t = Trace()
    t.emit("plan", plan_id=0, steps=Lazy(make))
    t.emit("push", plan_id=0, depth=1)
    assert calls == []  # nothing read them yet
    plan = t.of("plan")[0]
    assert plan["steps"] == ["at(a, p)"] and calls == [1]
    assert t.events[0]["steps"] == ["at(a, p)"] and calls == [1]  # made once
    assert [e["seq"] for e in t.events] == [0, 1]


def test_lazy_fields_are_written_to_the_file_at_once(tmp_path: Path) -> None:
    path = tmp_path / "t.jsonl"
    with Trace(path) as t:
        t.emit("plan", plan_id=3, goal=Lazy(lambda: ["g"]))
        rows = [json.loads(line) for line in path.read_text().splitlines()]
    assert rows[0]["goal"] == ["g"] and rows[0]["plan_id"] == 3


def test_a_run_trace_has_its_plan_records(tmp_path: Path) -> None:
    from nowplan.acting.run import run_episode
    from nowplan.domains.logistics.scenarios import episode
    from nowplan.acting.strategy import parse_strategy

    trace = Trace()
    run_episode(episode("small", seed=0), parse_strategy("hpn"), seed=0, trace=trace)
    plans = trace.of("plan")
    assert plans and all(isinstance(p["steps"], list) and isinstance(p["goal"], list) for p in plans)
    assert all("preimage" in s for p in plans for s in p["steps"])
