"""Flat logistics of growing size: nowplan's flat regression, nowplan's HPN with the
criticality file, Fast Downward (lama-first, through up-fast-downward) and pyperplan
(greedy best-first with h_FF), each under a time limit.

Writes benchmarks/results/flat_logistics.csv and .png.  Usage:

    .venv/bin/python benchmarks/flat_logistics.py [--time-limit 60] [--seeds 0,1] [--quick]

nowplan-flat uses the defaults of `nowplan plan` (weighted A* with w = 2, no HPN
shortcuts); nowplan-hpn uses the executive's defaults (A*, shortcuts on).
Times are wall-clock seconds of planning only (for HPN: the sum over all the plans
the executive made while solving the problem in a simulated world); cost is the
number of actions of the plan (for HPN: actions executed).  Compare ratios within one
run: the machine is shared and noisy.
"""

from __future__ import annotations

import argparse
import csv
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.levels import flat_levels
from nowplan.experiments import progress
from nowplan.domains.registry import Episode
from nowplan.io.logistics_gen import generate_logistics
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.worlds.symbolic import SymbolicWorld

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "logistics"
OUT = Path(__file__).resolve().parent / "results"
# (cities, locations per city, airplanes, packages)
SIZES = [(2, 2, 1, 2), (2, 3, 1, 4), (3, 3, 1, 6), (4, 3, 2, 8), (5, 3, 2, 10), (6, 4, 2, 14), (8, 4, 3, 20)]


def run_flat(dom: Path, prob: Path, limit: float) -> tuple[str, float, float | None]:
    p = load_pddl(dom, prob)
    t0 = time.perf_counter()
    # the defaults of `nowplan plan`: weighted A* (w = 2), no HPN shortcuts
    cfg = PlannerConfig(time_limit=limit, max_nodes=10**7, weight=2.0, serialization=False, monotonic=False)
    res = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), cfg)
    return res.status.value, time.perf_counter() - t0, float(len(res.plan)) if res.plan else None


def run_hpn(dom: Path, prob: Path, limit: float) -> tuple[str, float, float | None]:
    p = load_pddl(dom, prob, DATA / "logistics.crit")
    ep = Episode(p, SymbolicWorld(p.domain, p.init), SymbolicBelief(p.init))
    cfg = PlannerConfig(time_limit=limit)
    m = run_episode(ep, parse_strategy("hpn", time_limit=limit, max_actions=10_000, planner=cfg))
    # the executive's planning time is the sum of its planner calls
    return ("solved" if m.outcome.value == "reached" else m.outcome.value), m.planning_cpu_s, (
        m.execution_cost if m.outcome.value == "reached" else None)


def run_fd(dom: Path, prob: Path, limit: float) -> tuple[str, float, float | None]:
    from nowplan.planning.fd import solve_fd

    p = load_pddl(dom, prob)
    t0 = time.perf_counter()
    res = solve_fd(p, None, time_limit=limit)
    return res.status.value, time.perf_counter() - t0, float(len(res.plan)) if res.plan else None


def run_pyperplan(dom: Path, prob: Path, limit: float) -> tuple[str, float, float | None]:
    t0 = time.perf_counter()
    try:
        subprocess.run(
            [sys.executable, "-m", "pyperplan", "-H", "hff", "-s", "gbf", str(dom), str(prob)],
            capture_output=True, timeout=limit, check=False,
        )
    except subprocess.TimeoutExpired:
        return "time_limit", limit, None
    wall = time.perf_counter() - t0
    soln = Path(str(prob) + ".soln")
    if not soln.exists():
        return "unsolvable", wall, None
    steps = [ln for ln in soln.read_text().splitlines() if ln.strip().startswith("(")]
    soln.unlink()
    return "solved", wall, float(len(steps))


PLANNERS = {"nowplan-flat": run_flat, "nowplan-hpn": run_hpn, "fd-lama-first": run_fd, "pyperplan-gbf-hff": run_pyperplan}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--seeds", default="0,1")
    ap.add_argument("--quick", action="store_true", help="the first three sizes only")
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    sizes = SIZES[:3] if args.quick else SIZES
    args.out.mkdir(parents=True, exist_ok=True)
    rows: list[dict[str, object]] = []
    bar = progress.bar(len(sizes) * len(seeds) * len(PLANNERS), "flat_logistics")
    with tempfile.TemporaryDirectory() as tmp:
        for c, l, a, n in sizes:
            for seed in seeds:
                prob = Path(tmp) / f"p-c{c}-l{l}-a{a}-n{n}-s{seed}.pddl"
                prob.write_text(generate_logistics(c, l, a, n, seed=seed))
                for name, fn in PLANNERS.items():
                    bar.set_postfix_str(f"{n} packages, seed {seed}, {name}", refresh=False)
                    status, secs, cost = fn(DATA / "domain.pddl", prob, args.time_limit)
                    row = {"planner": name, "cities": c, "locations": l, "airplanes": a, "packages": n,
                           "seed": seed, "status": status, "seconds": round(secs, 4),
                           "cost": "" if cost is None else cost}
                    rows.append(row)
                    progress.echo(str(row))
                    bar.update(1)
    bar.close()
    csv_path = args.out / "flat_logistics.csv"
    with csv_path.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    (args.out / "machine.txt").write_text(
        f"{platform.node()} {platform.machine()} {platform.processor() or ''} python {platform.python_version()}\n"
        f"time limit {args.time_limit:g} s, seeds {args.seeds}\n"
    )
    plot(rows, args.out / "flat_logistics.png", args.time_limit)
    print(f"wrote {csv_path}")
    return 0


def plot(rows: list[dict[str, object]], path: Path, limit: float) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 4.5))
    for name in PLANNERS:
        pts: dict[int, list[float]] = {}
        for r in rows:
            if r["planner"] == name:
                secs = float(r["seconds"]) if r["status"] == "solved" else limit  # type: ignore[arg-type]
                pts.setdefault(int(r["packages"]), []).append(secs)  # type: ignore[arg-type]
        xs = sorted(pts)
        ax.plot(xs, [sum(pts[x]) / len(pts[x]) for x in xs], marker="o", label=name)
    ax.set_yscale("log")
    ax.set_xlabel("packages (cities and places grow with them)")
    ax.set_ylabel(f"planning time, s (log; unsolved = {limit:g})")
    ax.set_title("Flat logistics: planning time")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    sys.exit(main())
