"""The ``h2`` switch (planning/h2.py) against its absence, over stored held-out runs.

Reads the JSONL of ``benchmarks/heldout17.py`` (one row per level, strategy, seed) and prints, per
level, each strategy's reached runs, mean execution cost and mean CPU of the whole run (planning,
acting, the simulated world), and, paired by seed against ``--base``, on how many seeds each other
strategy costs less, the same, more.  The runs themselves:

    PYTHONPATH=src:examples/gridfix:benchmarks .venv/bin/python benchmarks/heldout17.py --seeds 0-39 \
        --time-limit 10 --levels clean,m0.15-p0.1,f0.2-m0.1-p0.05 --strategies hpn,hpn+h2 \
        --out benchmarks/results/h2_gridfix/runs.jsonl
    .venv/bin/python benchmarks/h2_ab.py benchmarks/results/h2_gridfix/runs.jsonl --base hpn

``--flat-pddl`` plans instead, with the regression engine at the concrete level (one call, A* with
h_add, HPN's shortcuts off; the compiled loop where it runs, ``--python`` for the Python loop only), the
shipped PDDL problems and the classical benchmark's p01-p03, without and with h2, and prints the
nodes expanded, the plan length and the CPU seconds of each call (the h² table's build included):

    PYTHONPATH=src .venv/bin/python benchmarks/h2_ab.py --flat-pddl --time-limit 30

``--build`` times the table (CPU: a regression call's set-up, which grounds the task, then ``PairReach``
and its first fixpoint)
on the first instance of each domain of ``benchmarks/criticality_auto.py``'s largest tier, generated
as that script does:

    .venv/bin/python benchmarks/h2_ab.py --build
"""

from __future__ import annotations

import argparse
import json
from collections import defaultdict
from pathlib import Path
from typing import Any


ROOT = Path(__file__).resolve().parents[1]


def flat_pddl(time_limit: float, native: bool) -> None:
    import gc
    from dataclasses import replace

    from nowplan.core.levels import flat_levels
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.regression import PlannerConfig, plan
    from nowplan.planning.regression_search import _Search

    _Search.native = native  # the compiled loop where it runs (as the planner does), or Python only
    pairs = [(d, p) for d in sorted((ROOT / "src/nowplan/data/pddl").iterdir()) if d.is_dir()
             for p in sorted(d.glob("p*.pddl"))]
    pairs += [(d, d / f"p0{i}.pddl") for d in sorted((ROOT / "benchmarks/classical").iterdir())
              if (d / "domain.pddl").exists() for i in (1, 2, 3) if (d / f"p0{i}.pddl").exists()]
    base = PlannerConfig(engine="regression", serialization=False, monotonic=False, prune=False,
                         max_nodes=10**7, time_limit=time_limit, clock="cpu")
    print("| problem | h2 off: status, nodes, length, CPU s | h2 on: status, nodes, length, CPU s | nodes on/off |")
    print("|---|---|---|---|")
    for d, p in pairs:
        cells = []
        nodes = []
        for h2 in (False, True):
            prob = load_pddl(d / "domain.pddl", p)  # a fresh domain: no table kept from the other run
            gc.collect()
            r = plan(prob.domain, prob.objects, prob.init, prob.goal, flat_levels(), replace(base, h2=h2))
            n = len(r.plan) if r.plan is not None else "-"
            cells.append(f"{r.status.name.lower()}, {r.expanded}, {n}, {r.cpu_time_s:.2f}")
            nodes.append(r.expanded if r.solved else None)
        ratio = f"{nodes[1] / nodes[0]:.2f}" if None not in nodes and nodes[0] else "-"
        print(f"| {d.name}/{p.stem} | {cells[0]} | {cells[1]} | {ratio} |", flush=True)


def build_times() -> None:
    import sys
    import tempfile
    import time

    for p in (ROOT, ROOT / "src"):  # this checkout's benchmarks package, as criticality_auto.py does
        if str(p) not in sys.path:
            sys.path.insert(0, str(p))
    from criticality_auto import LARGEST
    from benchmarks.classical.generate import domain_file, generate
    from nowplan.core.levels import flat_levels
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.h2 import MAX_ACTIONS, MAX_FACTS, PairReach, start_facts
    from nowplan.planning.heuristics import ground_task
    from nowplan.planning.regression import PlannerConfig
    from nowplan.planning.regression_search import _Search

    print("| instance | ground actions | participants | search set-up CPU s | table CPU s | sweeps | h2 runs |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for d, specs in LARGEST.items():
            params, seed = specs[0]
            path = Path(tmp) / f"{d}.pddl"
            path.write_text(generate(d, params, seed))
            prob = load_pddl(domain_file(d), path)
            c0 = time.process_time()  # (the search's set-up grounds the task for its h_add)
            srch = _Search(prob.domain, prob.objects, prob.init, flat_levels(), PlannerConfig(engine="regression"), None)
            task = ground_task(srch.grounder, srch.drop)
            c1 = time.process_time()
            pr = PairReach(task, prob.domain)
            pr.start_from(start_facts(srch.table, srch.belief, srch.true_ids()))
            c2 = time.process_time()
            runs = task.n <= MAX_ACTIONS and len(pr.fact_of) <= MAX_FACTS
            name = d + "-" + "-".join(str(v) for v in params.values())
            print(f"| {name} | {task.n} | {len(pr.fact_of)} | {c1 - c0:.2f} | {c2 - c1:.2f} | {pr.sweeps} | "
                  f"{'yes' if runs else 'no (too large)'} |", flush=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", type=Path, nargs="?", help="JSONL of benchmarks/heldout17.py")
    ap.add_argument("--base", default="hpn", help="the strategy the others are paired against")
    ap.add_argument("--flat-pddl", action="store_true", help="plan PDDL problems flat, h2 off and on")
    ap.add_argument("--time-limit", type=float, default=30.0, help="CPU seconds per call (--flat-pddl)")
    ap.add_argument("--python", action="store_true", help="--flat-pddl in the Python loop only")
    ap.add_argument("--build", action="store_true", help="time the table on the largest tier's instances")
    args = ap.parse_args(argv)
    if args.flat_pddl:
        flat_pddl(args.time_limit, not args.python)
        return 0
    if args.build:
        build_times()
        return 0
    if args.runs is None:
        ap.error("give the runs' JSONL, or --flat-pddl")
    rows: list[dict[str, Any]] = [json.loads(x) for x in args.runs.read_text().splitlines() if x.strip()]
    by: dict[str, dict[str, dict[int, dict[str, Any]]]] = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        by[r["level"]][r["strategy"]][int(r["seed"])] = r
    print(f"| level | strategy | reached | mean cost (reached) | mean run CPU s | vs {args.base}: cheaper / same / dearer |")
    print("|---|---|---|---|---|---|")
    for level in sorted(by):
        base = by[level].get(args.base, {})
        for strat in sorted(by[level]):
            rs = by[level][strat]
            ok = [r for r in rs.values() if r["outcome"] == "reached"]
            cost = sum(r["execution_cost"] for r in ok) / len(ok) if ok else float("nan")
            cpu = sum(r["cpu_s"] for r in rs.values()) / len(rs)
            pair = "-"
            if strat != args.base:
                w = s = lo = 0
                for seed, r in rs.items():
                    b = base.get(seed)
                    if b is None or r["outcome"] != "reached" or b["outcome"] != "reached":
                        continue
                    d = r["execution_cost"] - b["execution_cost"]
                    w, s, lo = w + (d < -1e-6), s + (abs(d) <= 1e-6), lo + (d > 1e-6)
                pair = f"{w} / {s} / {lo}"
            print(f"| {level} | {strat} | {len(ok)}/{len(rs)} | {cost:.1f} | {cpu:.3f} | {pair} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
