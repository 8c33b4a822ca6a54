"""The seed-003 verdict table (issue 17's targets) from synthetic runs: each bound decides its verdict."""

from __future__ import annotations

from typing import Any

from nowplan.domains.pieces.reproduction import RATES, STRATEGIES, _row, comparisons
from nowplan.experiments.verdicts import Verdict


def _runs(extra: dict[str, float], planning_s: dict[str, float]) -> dict[tuple[float, str], list[dict[str, Any]]]:
    runs: dict[tuple[float, str], list[dict[str, Any]]] = {}
    for rate in RATES:
        for label, _, _ in STRATEGIES:
            e = 0.0 if rate == 0 else extra.get(label, 10.0)
            runs[(rate, label)] = [{
                "extra": e, "travel": 70.0 + e, "moves": 12, "planning_s": planning_s.get(label, 0.02),
                "success": True, "believed_errors": 0, "frame_errors": 0, "relooks": 0, "disturbances": 1,
                "decisions": {},
            } for _ in range(3)]
    return runs


def _verdicts(extra: dict[str, float], planning_s: dict[str, float]) -> dict[str, Verdict]:
    runs = _runs(extra, planning_s)
    rows = [_row(rate, label, runs) for rate in RATES for label, _, _ in STRATEGIES]
    return {c.quantity: c.verdict for c in comparisons(rows, runs)}


def test_issue_17_targets_are_judged_on_pooled_runs() -> None:
    good = _verdicts({"replan to goal": 12.0, "always restore": 24.0, "seed rule + costs, warm library": 11.9},
                     {"seed rule, cold library": 0.015, "seed rule, warm library": 0.003})
    pooled = {k: v for k, v in good.items() if k.startswith(("pooled", "planning time"))}
    assert len(pooled) == 4
    assert pooled["pooled extra arm travel: seed rule + costs (warm) vs replanning to the goal, %"] is Verdict.MET
    assert pooled["pooled extra arm travel: seed rule + costs (warm) vs always restoring, %"] is Verdict.MET
    assert pooled["planning time, seed rule, cold library / its warm library (pooled), x"] is Verdict.MET
    assert pooled["planning time, replan to goal / its warm library (pooled), x"] is Verdict.NOT_MET  # 1x

    bad = _verdicts({"replan to goal": 12.0, "always restore": 15.0, "seed rule + costs, warm library": 12.5},
                    {"seed rule, cold library": 0.015, "seed rule, warm library": 0.010})
    assert bad["pooled extra arm travel: seed rule + costs (warm) vs replanning to the goal, %"] is Verdict.NOT_MET
    assert bad["pooled extra arm travel: seed rule + costs (warm) vs always restoring, %"] is Verdict.NOT_MET
    assert bad["planning time, seed rule, cold library / its warm library (pooled), x"] is Verdict.NOT_MET
