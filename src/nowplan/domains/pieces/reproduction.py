"""``nowplan reproduce 003``: does the seed's replanning rule save arm travel after disturbances?

Seed 003 reports no numbers, so the table is ours (issue 6).  Each problem
is an 8×8 board with 12 shuffled pieces, run through the camera loop (noisy
frames, the MLP recogniser, re-looks) while a person disturbs the board
after each piece move with probability 0, 0.1, 0.2 or 0.3.  Strategies,
all planning with the seed's means-ends planner:

* ``replan to goal``: after a surprise, plan from the observed model to the goal;
* ``always restore``: plan back to the expected model and continue (goal if impossible);
* ``seed rule, cold library``: the seed's thresholds; the library starts empty;
* ``seed rule, warm library``: the same, with a library filled by earlier runs
  of the same tasks (other disturbance seeds), read-only during measurement;
* ``cheapest alternative``: ours, plans every alternative and takes the cheapest.

Every strategy sees the same problems with the same camera and person seeds.
*Extra travel* is the arm's travel minus the undisturbed plan's cost: the
travel disturbances (and misrecognitions) cost.  The target (issue 6): the
seed's rule reduces extra travel by at least 25% against replanning to the
goal, with no more planning time.
"""

from __future__ import annotations

import logging
import sys
import tempfile
from collections import Counter
from dataclasses import replace
from pathlib import Path
from typing import Any

from nowplan.acting.hpn import Executive
from nowplan.acting.monitor import Monitor, MonitorConfig, monitor_settings
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.pieces.compare import means_ends_run, regression_run
from nowplan.domains.pieces.model import goal_reached
from nowplan.domains.pieces.scenarios import PiecesProblem, Size, generate, make_episode
from nowplan.domains.pieces.vision import Recognizer, misrecognised, recognizer
from nowplan.domains.pieces.world import PiecesWorld
from nowplan.experiments.reproductions import ReproductionOptions, ReproductionResult, ReproStatus
from nowplan.experiments.stats import estimate, markdown_table
from nowplan.planning.regression import PlannerConfig

log = logging.getLogger(__name__)

SIZE = Size(8, 8, 12)
RATES = (0.0, 0.1, 0.2, 0.3)
# label, monitor switch, library ("cold" or "warm")
STRATEGIES = (
    ("replan to goal", "monitor-goal", "cold"),
    ("always restore", "monitor-restore", "cold"),
    ("seed rule, cold library", "monitor", "cold"),
    ("seed rule, warm library", "monitor", "warm"),
    ("cheapest alternative (ours)", "monitor-cost", "cold"),
)
BASELINE = "replan to goal"
RULE_ROWS = ("seed rule, cold library", "seed rule, warm library")
TARGET_REDUCTION = 0.25


def run_episode_003(task: PiecesProblem, rate: float, seed: int, switch: str, rec: Recognizer,
                    config: MonitorConfig) -> dict[str, Any]:
    """One run; returns its measurements (travel from the true world, errors against the truth)."""
    ep = make_episode(task, seed, rate, rec=rec)
    world: PiecesWorld = ep.world
    strategy = replace(parse_strategy(f"hpn+{switch}", max_actions=400, time_limit=120.0),
                       planner=PlannerConfig(time_limit=10.0, seed=seed))
    with monitor_settings(config):
        ex = Executive(ep.problem, world, ep.belief, strategy, seed=seed)
    m = ex.run()
    mon = next(x for x in ex.mechanisms if isinstance(x, Monitor))
    log_ = ep.belief.log
    believed_errors = sum(len(misrecognised(lab, _truth(world, fid))) for fid, lab in log_.updates)
    frame_errors = sum(len(misrecognised(lab, _truth(world, fid))) for fid, lab in log_.frames)
    return {
        "success": goal_reached(world.board, task.goal),
        "outcome": m.outcome.value, "reason": m.reason,
        "travel": world.travel, "moves": world.piece_moves, "planning_s": m.planning_cpu_s,
        "disturbances": world.exogenous_events, "surprises": mon.stats.surprises,
        "decisions": dict(mon.stats.decisions), "reuses": mon.stats.reuses,
        "believed_errors": believed_errors, "frame_errors": frame_errors,
        "frames": log_.looks, "relooks": log_.relooks, "cleared": log_.cleared_by_relook,
    }


def _truth(world: PiecesWorld, frame: int) -> Any:
    from nowplan.domains.pieces.board import Board

    return Board.of(world.board.geometry, {c: k for c, k in world.truth[frame].items() if k != "empty"},
                    world.board.arm)


def reproduce_003(options: ReproductionOptions) -> ReproductionResult:
    problems = 4 if options.quick else 16
    warmups = 2 if options.quick else 4
    tasks = [generate(SIZE, 300 + i, "pieces-003") for i in range(problems)]
    rec = recognizer(0)
    nominal = {t.name: means_ends_run(t).cost for t in tasks}
    tmp = tempfile.TemporaryDirectory(prefix="nowplan-003-")
    lib_dir = options.out_dir if options.out_dir is not None else Path(tmp.name)
    lib_dir.mkdir(parents=True, exist_ok=True)
    lib_path = lib_dir / "plan_library_003.sqlite"
    if lib_path.exists():
        lib_path.unlink()  # a fresh warm-up, so the table does not depend on earlier invocations
    total = len(tasks) * len(RATES) * (len(STRATEGIES) + warmups)
    bar = _progress(total)
    warm_cfg = MonitorConfig(library_path=str(lib_path), library_write=True)
    for t in tasks:  # warm-up runs of the seed's rule, with other camera and person seeds
        for rate in RATES:
            for k in range(warmups):
                run_episode_003(t, rate, 5000 + 97 * k, "monitor", rec, warm_cfg)
                bar.update(1)
    runs: dict[tuple[float, str], list[dict[str, Any]]] = {}
    for rate in RATES:
        for label, switch, lib in STRATEGIES:
            cfg = MonitorConfig(library_path=str(lib_path), library_write=False) if lib == "warm" \
                else MonitorConfig()
            out = []
            for i, t in enumerate(tasks):
                r = run_episode_003(t, rate, 11 + i, switch, rec, cfg)
                r["extra"] = r["travel"] - nominal[t.name]
                out.append(r)
                bar.update(1)
            runs[(rate, label)] = out
    bar.close()
    rows = [_row(rate, label, runs) for rate in RATES for label, _, _ in STRATEGIES]
    planners = _planner_comparison(options.quick)
    notes = _notes(rows, rec, problems, warmups, planners)
    result = ReproductionResult("003", ReproStatus.DONE, rows=rows, notes=notes)
    if options.out_dir is not None:
        result.outputs.append(_write(options.out_dir, rows, planners, notes))
    tmp.cleanup()
    return result


def _progress(total: int) -> Any:
    from tqdm import tqdm

    return tqdm(total=total, desc="reproduce 003", file=sys.stderr, disable=None, leave=False)


def _row(rate: float, label: str, runs: dict[tuple[float, str], list[dict[str, Any]]]) -> dict[str, Any]:
    rs = runs[(rate, label)]
    base = runs[(rate, BASELINE)]
    extra = estimate([r["extra"] for r in rs])
    base_extra = estimate([r["extra"] for r in base]).mean
    decisions: Counter[str] = Counter()
    for r in rs:
        decisions.update(r["decisions"])
    vs = None if label == BASELINE or base_extra <= 0 else round(100.0 * (extra.mean / base_extra - 1.0), 1)
    return {
        "disturbance": rate,
        "strategy": label,
        "arm_travel": estimate([r["travel"] for r in rs]).fmt(4),
        "extra_travel": extra.fmt(3),
        "extra_vs_goal_pct": vs,
        "moves": round(estimate([r["moves"] for r in rs]).mean, 2),
        "planning_ms": round(1000 * estimate([r["planning_s"] for r in rs]).mean, 2),
        "success_pct": round(100.0 * sum(r["success"] for r in rs) / len(rs), 1),
        "recognition_errors": round(estimate([r["believed_errors"] for r in rs]).mean, 2),
        "frame_errors": round(estimate([r["frame_errors"] for r in rs]).mean, 2),
        "relooks": round(estimate([r["relooks"] for r in rs]).mean, 1),
        "disturbances_seen": round(estimate([r["disturbances"] for r in rs]).mean, 2),
        "choices": ", ".join(f"{k} {v}" for k, v in sorted(decisions.items())) or "–",
    }


def _planner_comparison(quick: bool) -> list[dict[str, Any]]:
    n, limit = (3, 20.0) if quick else (10, 60.0)
    out = []
    for i in range(n):
        t = generate(Size(8, 8, 6), 700 + i, "pieces-planners")
        a, b = means_ends_run(t), regression_run(t, hierarchical=False, time_limit=limit)
        for run in (a, b):
            out.append({"problem": t.name, "planner": run.planner, "solved": run.solved,
                        "cost": round(run.cost, 2) if run.solved else None,
                        "cpu_s": round(run.cpu_s, 3), "reason": run.reason})
    return out


def _notes(rows: list[dict[str, Any]], rec: Recognizer, problems: int, warmups: int,
           planners: list[dict[str, Any]]) -> str:
    verdicts = []
    for rate in RATES[1:]:
        base = next(r for r in rows if r["disturbance"] == rate and r["strategy"] == BASELINE)
        for label in RULE_ROWS:
            r = next(x for x in rows if x["disturbance"] == rate and x["strategy"] == label)
            change = r["extra_vs_goal_pct"]
            ok = change is not None and change <= -100 * TARGET_REDUCTION \
                and r["planning_ms"] <= base["planning_ms"]
            what = "n/a (no extra travel to compare)" if change is None else f"{change:+.1f}% extra travel"
            verdicts.append(f"p={rate:g} {label}: {what} vs replanning to the goal, planning "
                            f"{r['planning_ms']} vs {base['planning_ms']} ms -> "
                            f"{'target met' if ok else 'target NOT met'}")
    cmp_text = planner_summary(planners)
    return (
        f"{problems} problems (8×8, 12 pieces, seeds 300–{299 + problems}) per row, each strategy with the "
        f"same camera and person seeds; warm library: {warmups} earlier runs of the seed's rule per task and "
        f"rate. {rec.summary()}. Extra travel = arm travel − undisturbed plan cost; extra_vs_goal_pct = change "
        f"against 'replan to goal' (negative is better). Target (≥{100 * TARGET_REDUCTION:.0f}% less extra "
        f"travel than replanning to the goal, no more planning time): " + "; ".join(verdicts) + ". "
        "Not run: 'flexible execution with serendipity' (seed 000 switches flexible+serendipity) acts on "
        "plans from the executive's regression planner, which does not solve these 8×8 problems in usable "
        "time (see the planner comparison), and the executive cannot take the domain's planner yet; its "
        "row is therefore not available. Planner comparison (8×8, 6 pieces; regression flat over the "
        f"relevant cells): {cmp_text}. The seed itself reports no numbers."
    )


def planner_summary(planners: list[dict[str, Any]]) -> str:
    """Solved counts, mean cost on the problems every planner solved, mean CPU time."""
    names = sorted({p["planner"] for p in planners})
    problems = sorted({p["problem"] for p in planners})
    common = [pb for pb in problems
              if all(any(x["problem"] == pb and x["planner"] == n and x["solved"] for x in planners)
                     for n in names)]
    parts = []
    for n in names:
        mine = [x for x in planners if x["planner"] == n]
        parts.append(
            f"{n}: solved {sum(x['solved'] for x in mine)}/{len(mine)}, mean cost on the {len(common)} "
            f"problem(s) all solved {_mean([x['cost'] for x in mine if x['problem'] in common])}, "
            f"mean CPU {_mean([x['cpu_s'] for x in mine])} s"
        )
    return "; ".join(parts)


def _mean(xs: list[float]) -> str:
    return f"{sum(xs) / len(xs):.3g}" if xs else "–"


def _write(out_dir: Path, rows: list[dict[str, Any]], planners: list[dict[str, Any]], notes: str) -> Path:
    out_dir.mkdir(parents=True, exist_ok=True)
    cols = list(rows[0])
    text = ["# Seed 003: replanning after disturbances on shuffled pieces", "",
            markdown_table(cols, [[str(r[c]) for c in cols] for r in rows]), "",
            "## Planners on the same problems", "",
            markdown_table(list(planners[0]), [[str(p[c]) for c in planners[0]] for p in planners]), "",
            notes, ""]
    path = out_dir / "table_003.md"
    path.write_text("\n".join(text), encoding="utf-8")
    return path
