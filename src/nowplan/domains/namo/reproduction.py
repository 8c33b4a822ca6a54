"""``nowplan reproduce 000``: seed 000's Table I on the NAMO domains, plus the office run.

Original BHPN (replan only on failure), aggressive replanning (replan after
every action) and selective replanning (domain triggers and cost increases),
all with foresight, as the paper's Table I compares them, over domains 1-3
with several seeded runs each.  Per domain and algorithm: mean picks/places
(``Pick`` + ``Place`` actions), looks (every ``Look*`` action), moves
(``Move`` actions), and time relative to the original BHPN's on the same
domain, both as planning CPU time and as the run's total CPU time (planning,
triggers, simulated perception and belief updates).  The office run follows.
Runs go to worker processes (``--jobs``), each seeded, so results do not
depend on the number of workers.  Each run is timed ``TIMING_REPEATS``
times and the fastest counts: the machine is shared, and other processes
only ever add time.
"""

from __future__ import annotations

import logging
import math
import os
import time
from collections.abc import Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, replace
from typing import Any

from nowplan.acting.strategy import parse_strategy
from nowplan.experiments.reproductions import (
    ReproductionOptions,
    ReproductionResult,
    ReproStatus,
    side_by_side,
)
from nowplan.experiments import progress
from nowplan.experiments.verdicts import Comparison, judged
from nowplan.planning.regression import PlannerConfig

log = logging.getLogger(__name__)

# Sec. V: "All the algorithms include the foresight mechanisms ...; they differ in their approach to
# reconsideration."  All three execute plans flexibly (Fig. 4: retry a step whose pre-image still
# holds, skip a step whose result already holds), which Sec. III-A counts as "implemented in the
# current BHPN"; the novel mechanisms (serendipity across levels, selective triggers) are not in
# the original BHPN.
ALGORITHMS = {
    "original BHPN": "hpn+flexible+foresight",
    "aggressive replanning": "hpn+flexible+foresight+aggressive",
    "selective replanning": "hpn+flexible+foresight+selective",
}
# Sec. V: selective replanning "triggers replanning when new objects are discovered and when a new
# path to the goal is shorter than the existing plan by one meter" -- the domain's two-stage triggers
# (triggers.py), without the executive's generic cost-increase trigger
SETTINGS: dict[str, dict[str, Any]] = {"selective replanning": {"cost_increase": math.inf}}
DOMAINS = {"1": "domain1", "2": "domain2", "3": "domain3"}
PLANNER = PlannerConfig(max_nodes=4000, shortcut_nodes=600, time_limit=20.0)


@dataclass(frozen=True)
class RunSpec:
    domain: str  # label: "1", "2", "3" or "office"
    scenario: str
    algorithm: str
    seed: int


TIMING_REPEATS = 3  # each run is repeated and timed this often; the fastest counts (see run_one)


def _once(spec: RunSpec) -> tuple[dict[str, Any], tuple[Any, ...]]:
    from nowplan.acting.run import run_episode
    from nowplan.domains.namo.scenarios import SCENARIOS, episode

    scen = SCENARIOS.spec(spec.scenario)
    ep = episode(scen, spec.seed)
    strategy = parse_strategy(
        ALGORITHMS[spec.algorithm], max_actions=scen.max_actions, max_plans=800, time_limit=240.0,
    )
    strategy = replace(strategy, planner=replace(PLANNER, seed=spec.seed), **SETTINGS.get(spec.algorithm, {}))
    cpu0 = time.process_time()
    m = run_episode(ep, strategy, seed=spec.seed)
    cpu = time.process_time() - cpu0
    c = m.action_counts
    record = {
        "domain": spec.domain, "algorithm": spec.algorithm, "seed": spec.seed,
        "outcome": m.outcome.value, "reason": m.reason,
        "picks_places": c["Pick"] + c["Place"],
        "looks": sum(v for k, v in c.items() if k.startswith("Look")),
        "moves": c["Move"], "drives": ep.world.drives, "actions": m.actions,
        "planning_cpu_s": m.planning_cpu_s, "run_cpu_s": cpu, "plans": m.plans_made, "replans": m.replans,
        "objects": len(ep.world.objects),
    }
    return record, (m.outcome.value, m.actions, tuple(sorted(c.items())), m.plans_made)


def run_one(spec: RunSpec, repeats: int = TIMING_REPEATS) -> dict[str, Any]:
    """One seeded run in this process; returns a JSON-able record.

    A run is deterministic given its seed, so it is repeated ``repeats``
    times and the smallest CPU times are kept (the usual defence against
    other processes on a shared machine, which only ever add time); the
    record says how far the repeats' planning times spread.  If a repeat
    behaved differently the first run's record is kept as it is.
    """
    record, behaviour = _once(spec)
    plans = [record["planning_cpu_s"]]
    runs = [record["run_cpu_s"]]
    for _ in range(max(repeats, 1) - 1):
        again, same = _once(spec)
        if same != behaviour:
            log.warning("run %s behaved differently when repeated; keeping the first", spec)
            record["repeat_mismatch"] = True
            return record
        plans.append(again["planning_cpu_s"])
        runs.append(again["run_cpu_s"])
    record["planning_cpu_s"], record["run_cpu_s"] = min(plans), min(runs)
    record["planning_cpu_spread"] = round(max(plans) / min(plans), 3) if min(plans) > 0 else None
    return record


def _runs(options: ReproductionOptions) -> list[RunSpec]:
    seeds = range(3) if options.quick else range(10)
    out = [RunSpec(label, scen, alg, s) for label, scen in DOMAINS.items() for alg in ALGORITHMS for s in seeds]
    office_algs = ["selective replanning"] if options.quick else list(ALGORITHMS)
    office_seeds = range(1) if options.quick else range(3)
    out += [RunSpec("office", "office", alg, s) for alg in office_algs for s in office_seeds]
    return out


def _execute(specs: Sequence[RunSpec], jobs: int, bar: Any) -> list[dict[str, Any]]:
    out = []
    if jobs <= 1:
        for s in specs:
            out.append(run_one(s))
            bar.update(1)
        return out
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        for rec in pool.map(run_one, specs):  # in order, so the records do not depend on the workers
            out.append(rec)
            bar.update(1)
    return out


def _mean(xs: Sequence[float]) -> float | None:
    return sum(xs) / len(xs) if xs else None


def aggregate(records: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Rows per (domain, algorithm) with means over the runs that reached the goal, and an Avg row."""
    rows: list[dict[str, Any]] = []
    labels = [d for d in DOMAINS] + (["office"] if any(r["domain"] == "office" for r in records) else [])
    base: dict[str, tuple[float, float]] = {}
    for label in labels:
        for alg in ALGORITHMS:
            rs = [r for r in records if r["domain"] == label and r["algorithm"] == alg]
            if not rs:
                continue
            ok = [r for r in rs if r["outcome"] == "reached"]
            row: dict[str, Any] = {"domain": label, "algorithm": alg, "reached": f"{len(ok)}/{len(rs)}"}
            for key in ("picks_places", "looks", "moves", "drives"):
                v = _mean([r.get(key, 0) for r in ok])
                row[key] = None if v is None else round(v, 2)
            # time over all runs (a run that failed still spent it)
            plan_t = _mean([r["planning_cpu_s"] for r in rs]) or 0.0
            run_t = _mean([r["run_cpu_s"] for r in rs]) or 0.0
            if alg == "original BHPN":
                base[label] = (plan_t, run_t)
            b = base.get(label)
            row["time_ratio"] = round(run_t / b[1], 2) if b and b[1] > 0 else None
            row["planning_ratio"] = round(plan_t / b[0], 2) if b and b[0] > 0 else None
            row["run_cpu_s"] = round(run_t, 3)
            row["planning_cpu_s"] = round(plan_t, 4)
            rows.append(row)
    for alg in ALGORITHMS:
        rs = [r for r in rows if r["algorithm"] == alg and r["domain"] in DOMAINS]
        if not rs:
            continue
        avg: dict[str, Any] = {"domain": "Avg", "algorithm": alg}
        for key in ("picks_places", "looks", "moves", "drives"):
            vals = [r[key] for r in rs if r[key] is not None]
            avg[key] = round(sum(vals) / len(vals), 2) if vals else None
        # the paper's Avg time is total time over total baseline time (Table I: selective
        # (0.57*1265 + 1.06*1020 + 0.89*850) / (1265 + 1020 + 850) = 0.81), i.e. the ratio of the
        # summed per-domain mean times; the mean of the per-domain ratios is kept beside it
        origs = {r["domain"]: r for r in rows if r["algorithm"] == "original BHPN" and r["domain"] in DOMAINS}
        pairs = [(r, origs[r["domain"]]) for r in rs if r["domain"] in origs]
        for key, col in (("time_ratio", "run_cpu_s"), ("planning_ratio", "planning_cpu_s")):
            own, ref = sum(r[col] for r, _ in pairs), sum(o[col] for _, o in pairs)
            avg[key] = round(own / ref, 2) if pairs and ref > 0 else None
            vals = [r[key] for r in rs if r[key] is not None]
            avg[key + "_mean"] = round(sum(vals) / len(vals), 2) if vals else None
        n_ok = sum(int(r["reached"].split("/")[0]) for r in rs)
        n_all = sum(int(r["reached"].split("/")[1]) for r in rs)
        avg["reached"] = f"{n_ok}/{n_all}"
        rows.append(avg)
    return rows


# issue 17: selective replanning's planning time on domain 2 at most this multiple of the original's
# (Table I: 1.06)
DOMAIN2_TARGET = 1.1


def domain_ratio(rows: Sequence[dict[str, Any]], domain: str) -> float | None:
    """Selective replanning's planning time over the original BHPN's on one domain (None: no runs)."""
    for r in rows:
        if r["domain"] == domain and r["algorithm"] == "selective replanning":
            v = r.get("planning_ratio")
            return None if v is None else float(v)
    return None


def targets(rows: Sequence[dict[str, Any]]) -> list[str]:
    """The issue's targets, checked on the Avg rows: each line says met or not met, with the numbers."""
    avg = {r["algorithm"]: r for r in rows if r["domain"] == "Avg"}
    o, a, s = avg.get("original BHPN"), avg.get("aggressive replanning"), avg.get("selective replanning")
    if not (o and a and s) or s["planning_ratio"] is None or a["planning_ratio"] is None:
        return ["targets: not enough runs reached the goal to check them"]
    out = []
    sel, agg = s["planning_ratio"], a["planning_ratio"]
    d2 = domain_ratio(rows, "2")
    if d2 is not None:
        out.append(f"selective planning time on domain 2 {d2:.2f}x original's (target <= {DOMAIN2_TARGET}): "
                   f"{'met' if d2 <= DOMAIN2_TARGET + 1e-9 else 'NOT met'}")
    out.append(f"selective planning time {sel:.2f}x original's (target <= 0.7): {'met' if sel <= 0.7 else 'NOT met'}")
    rel = sel / agg if agg else float("inf")
    out.append(f"selective planning time {rel:.2f}x aggressive's (target <= 0.5): {'met' if rel <= 0.5 else 'NOT met'}")
    for key in ("picks_places", "looks", "moves"):
        if s[key] is not None and a[key] is not None:
            ok = s[key] <= a[key] + 1e-9
            out.append(f"selective {key} {s[key]} vs aggressive {a[key]} (target: no higher): {'met' if ok else 'NOT met'}")
    return out


def comparisons(rows: Sequence[dict[str, Any]]) -> list[Comparison]:
    """The issue's targets on the Avg rows, ours beside Table I's Avg row."""
    from nowplan.experiments.papers import PAPERS

    avg = {r["algorithm"]: r for r in rows if r["domain"] == "Avg"}
    paper = {r["algorithm"]: r for r in PAPERS["000"].rows if r["domain"] == "Avg"}
    o, a, s = avg.get("original BHPN"), avg.get("aggressive replanning"), avg.get("selective replanning")
    if not (o and a and s):
        return []
    ps, pa = paper["selective replanning"], paper["aggressive replanning"]
    sel, agg = s.get("planning_ratio"), a.get("planning_ratio")
    p2 = next(r for r in PAPERS["000"].rows if r["domain"] == "2" and r["algorithm"] == "selective replanning")
    out = [
        judged("selective / original BHPN planning time (domain 2)", domain_ratio(rows, "2"), p2["time_ratio"],
               at_most=DOMAIN2_TARGET, target=f"<= {DOMAIN2_TARGET}"),
        judged("selective / original BHPN planning time (Avg)", sel, ps["time_ratio"], at_most=0.7,
               target="<= 0.7"),
        judged("selective / aggressive planning time (Avg)", round(sel / agg, 2) if sel is not None and agg else None,
               round(ps["time_ratio"] / pa["time_ratio"], 2), at_most=0.5, target="<= 0.5"),
    ]
    for key, label in (("picks_places", "picks/places"), ("looks", "looks"), ("moves", "moves")):
        if s[key] is not None and a[key] is not None:
            out.append(judged(f"selective {label} per run (Avg)", s[key], ps[key], at_most=a[key],
                              target=f"<= aggressive's ({a[key]:g})"))
    return out


def reproduce_000(options: ReproductionOptions) -> ReproductionResult:
    jobs = options.jobs or min(2, os.cpu_count() or 1)
    bar = progress.bar(None, "reproduce 000")  # drawn now; the total is known once the runs are listed
    specs = _runs(options)
    bar.reset(total=len(specs))
    log.info("seed 000: %d runs on %d worker(s)", len(specs), jobs)
    t0 = time.perf_counter()
    records = _execute(specs, jobs, bar)
    bar.close()
    elapsed = time.perf_counter() - t0
    rows = aggregate(records)
    checks = targets(rows)
    office = [r for r in records if r["domain"] == "office"]
    notes = [
        f"{len(records)} runs ({'quick' if options.quick else 'full'}: seeds "
        f"{'0-2' if options.quick else '0-9'} per domain and algorithm), {elapsed:.0f} s wall on {jobs} worker(s).",
        f"Each run is deterministic given its seed and was timed {TIMING_REPEATS} times; the fastest counts. "
        "Means over runs that reached the goal; time ratios over all runs, relative to the original BHPN on "
        "the same domain: time_ratio = the whole run's CPU time (planning, triggers, simulated perception, "
        "belief updates), planning_ratio = the planner's CPU time only. The paper's time is total simulated "
        "execution time of a PR2 simulation with an RRT, so only the ratios are comparable. Avg ratios are, as "
        "in the paper's Table I, summed time over summed original time across domains 1-3 (the mean of the "
        "per-domain ratios is in the *_mean columns).",
        "Setting differences: 2-D disc robot and box obstacles on a 0.2 m grid (not a PR2); the maps are in "
        "the spirit of Fig. 10, not copies; base motion inside Pick/Place (approach, drag, return) is part of "
        "those actions, so 'moves' counts only Move actions and 'drives' counts every base motion (moves plus the "
        "approach and return drives of picks and places); all algorithms use foresight and the flexible "
        "execution of Fig. 4 (none uses serendipity); selective replanning fires only the domain's two-stage triggers of Sec. IV-B/V (a new "
        "obstacle on the path or a better estimate -> a path cheaper by 1 m -> replan), not the executive's "
        "generic cost-increase trigger (see docs/namo.md).",
        *checks,
    ]
    if office:
        parts = [f"{r['algorithm']} seed {r['seed']}: {r['outcome']}, {r['objects']} objects, "
                 f"{r['picks_places'] // 2} object displacement(s), {r['moves']} moves" for r in office]
        notes.append("Office (paper: reached with two object displacements): " + "; ".join(parts) + ".")
    result = ReproductionResult(
        seed="000", status=ReproStatus.DONE, rows=rows, notes="\n".join(notes),
        title="seed 000: BHPN reconsideration on NAMO (Table I)", comparisons=comparisons(rows),
    )
    if options.out_dir is not None:
        result.outputs = write_outputs(options.out_dir, rows, records, notes)
    return result


def write_outputs(out_dir: Any, rows: Sequence[dict[str, Any]], records: Sequence[dict[str, Any]],
                  notes: Sequence[str]) -> list[Any]:
    import json
    from pathlib import Path

    from nowplan.experiments.papers import PAPERS
    from nowplan.experiments.report import Block, Heading, Paragraph, write_report

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    ours = [{k: v for k, v in r.items() if k in ("domain", "algorithm", "picks_places", "looks", "moves",
                                                   "planning_ratio", "time_ratio")} for r in rows if r["domain"] != "office"]
    paper = [dict(r) for r in PAPERS["000"].rows]
    blocks: list[Block] = [
        Heading("Seed 000, Table I: ours beside the paper's", 1),
        side_by_side(ours, paper, ["domain", "algorithm"], "picks/places, looks, moves, time relative to original"),
        Heading("All our rows"),
        side_by_side(list(rows), [], ["domain", "algorithm"]),
        *(Paragraph(n) for n in notes),
    ]
    files = write_report(blocks, out)
    runs = out / "runs.json"
    runs.write_text(json.dumps(list(records), indent=1), encoding="utf-8")
    return [files.markdown, files.html, runs]


def fastest_of(runs: Sequence[Sequence[dict[str, Any]]]) -> list[dict[str, Any]]:
    """Records of several reproductions merged run by run, keeping each run's fastest CPU times.

    The same rule as the fastest of ``TIMING_REPEATS`` timings within one
    reproduction (other processes only ever add time); only valid when every
    run behaved the same in all of them, which is checked.
    """
    merged: dict[tuple[str, str, int], dict[str, Any]] = {}
    for records in runs:
        for r in records:
            key = (r["domain"], r["algorithm"], r["seed"])
            had = merged.get(key)
            if had is None:
                merged[key] = dict(r)
                continue
            same = all(had[k] == r[k] for k in ("outcome", "actions", "picks_places", "looks", "moves", "plans"))
            if not same:
                from nowplan.errors import UsageError

                raise UsageError(f"run {key} behaved differently in two of the runs.json files given; "
                                 "merge only reproductions of the same code")
            had["planning_cpu_s"] = min(had["planning_cpu_s"], r["planning_cpu_s"])
            had["run_cpu_s"] = min(had["run_cpu_s"], r["run_cpu_s"])
    return list(merged.values())

