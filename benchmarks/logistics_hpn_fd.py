"""HPN's planning time on logistics against Fast Downward lama-first (issue 19, target 4).

For each generated logistics problem (the sizes of benchmarks/flat_logistics.py):

* ``hpn``: the executive with ``logistics.crit`` solving the problem in a simulated
  world; its time is the CPU time of all its planner calls (the regression planner on
  HPN's abstract levels, the forward engine on concrete calls);
* ``flat``: one flat ``plan()`` call with the defaults of ``nowplan plan`` (forward LAMA
  search, no anytime improvement), in-process CPU time;
* ``fd``: lama-first as a process (benchmarks/classical/harness.py), wall time with its
  start-up, and its search time alone (FD's "Search time" line is not read; its
  "Planner time", without the translator's start-up, is).

Target 4: at 20 packages HPN's total planning time is at most 1/5 of lama-first's.
Writes ``logistics_hpn_fd.csv`` and ``.md`` to ``--out``.

    .venv/bin/python benchmarks/logistics_hpn_fd.py --packages 8,14,20 --seeds 0,1
"""

from __future__ import annotations

import argparse
import csv
import platform
import resource
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from benchmarks.classical.harness import run_fd  # noqa: E402
from nowplan.acting.run import run_episode  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.belief.symbolic import SymbolicBelief  # noqa: E402
from nowplan.core.levels import flat_levels  # noqa: E402
from nowplan.experiments import progress  # noqa: E402
from nowplan.domains.registry import Episode  # noqa: E402
from nowplan.io.logistics_gen import generate_logistics  # noqa: E402
from nowplan.io.pddl_read import load_pddl  # noqa: E402
from nowplan.planning.regression import PlannerConfig, plan  # noqa: E402
from nowplan.worlds.symbolic import SymbolicWorld  # noqa: E402

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "logistics"
# packages -> (cities, locations per city, airplanes), as in flat_logistics.py
SIZES = {2: (2, 2, 1), 4: (2, 3, 1), 6: (3, 3, 1), 8: (4, 3, 2), 10: (5, 3, 2), 14: (6, 4, 2), 20: (8, 4, 3)}


def _children_cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def run_hpn(prob: Path, limit: float, strategy: str = "hpn") -> tuple[bool, float, float]:
    p = load_pddl(DATA / "domain.pddl", prob, DATA / "logistics.crit")
    ep = Episode(p, SymbolicWorld(p.domain, p.init), SymbolicBelief(p.init))
    m = run_episode(ep, parse_strategy(strategy, time_limit=limit, max_actions=10_000,
                                       planner=PlannerConfig(time_limit=limit)))
    return m.outcome.value == "reached", m.planning_cpu_s, m.execution_cost


def run_flat(prob: Path, limit: float) -> tuple[bool, float, float]:
    p = load_pddl(DATA / "domain.pddl", prob)
    t = time.process_time()
    res = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), PlannerConfig(time_limit=limit))
    return res.solved, time.process_time() - t, res.plan.cost(p.init) if res.plan else float("nan")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--packages", default="8,14,20")
    ap.add_argument("--seeds", default="0,1")
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--strategy", default="hpn", help="HPN's strategy (e.g. hpn+nodirect: no direct refinements)")
    ap.add_argument("--out", type=Path, default=Path(__file__).resolve().parent / "results")
    args = ap.parse_args()
    rows: list[dict[str, object]] = []
    sizes, seeds = [int(x) for x in args.packages.split(",")], [int(s) for s in args.seeds.split(",")]
    bar = progress.bar(len(sizes) * len(seeds), "logistics_hpn_fd", unit="problem")
    with tempfile.TemporaryDirectory() as tmp:
        for n in sizes:
            c, loc, air = SIZES[n]
            for seed in seeds:
                bar.set_postfix_str(f"{n} packages, seed {seed}", refresh=False)
                prob = Path(tmp) / f"logistics-{n}-{seed}.pddl"
                prob.write_text(generate_logistics(c, loc, air, n, seed=seed))
                ok_h, t_h, c_h = run_hpn(prob, args.time_limit, args.strategy)
                ok_f, t_f, c_f = run_flat(prob, args.time_limit)
                fd_cpu = _children_cpu()
                fd = run_fd(DATA / "domain.pddl", prob, args.time_limit)
                fd_cpu = _children_cpu() - fd_cpu  # FD's processes' CPU: what load does not inflate
                row: dict[str, object] = {"packages": n, "seed": seed, "hpn_ok": ok_h, "hpn_cpu_s": round(t_h, 3), "hpn_cost": c_h,
                       "flat_ok": ok_f, "flat_cpu_s": round(t_f, 3), "flat_cost": c_f,
                       "fd_ok": fd.solved, "fd_wall_s": round(fd.wall_s, 3), "fd_cost": fd.cost,
                       "hpn_over_fd": round(t_h / fd.wall_s, 3) if fd.solved else "",
                       "fd_cpu_s": round(fd_cpu, 3),
                       "hpn_over_fd_cpu": round(t_h / fd_cpu, 3) if fd.solved and fd_cpu > 0 else ""}
                rows.append(row)
                progress.echo(str(row))
                bar.update(1)
    bar.close()
    args.out.mkdir(parents=True, exist_ok=True)
    with (args.out / "logistics_hpn_fd.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = [
        "# HPN and nowplan's flat planner against lama-first on logistics (issue 19, target 4)",
        "",
        f"`{' '.join(sys.argv)}` on {platform.machine()}, python {platform.python_version()};"
        " CPU seconds for nowplan (in-process), wall seconds with start-up for FD, and the CPU seconds"
        " of FD's processes (user + system; on a loaded machine the wall time grows and these do not).",
        "",
        "| packages | seed | HPN planning CPU s (cost) | flat CPU s (cost) | lama-first wall s (cost) | HPN / FD |"
        " lama-first CPU s | HPN / FD CPU |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(f"| {r['packages']} | {r['seed']} | {r['hpn_cpu_s']} ({r['hpn_cost']:g}) | "
                     f"{r['flat_cpu_s']} ({r['flat_cost']:g}) | {r['fd_wall_s']} ({r['fd_cost']}) | "
                     f"{r['hpn_over_fd']} | {r['fd_cpu_s']} | {r['hpn_over_fd_cpu']} |")
    big = [r for r in rows if r["packages"] == max(int(x) for x in args.packages.split(",")) and r["hpn_over_fd"] != ""]
    if big:
        worst = max(float(str(r["hpn_over_fd"])) for r in big)
        verdict = "met" if worst <= 0.2 else "not met"
        lines += ["", f"Target 4 (HPN ≤ 1/5 of lama-first at {big[0]['packages']} packages): worst ratio "
                      f"{worst:.2f} — **{verdict}**."]
        cpu = [float(str(r["hpn_over_fd_cpu"])) for r in big if r["hpn_over_fd_cpu"] != ""]
        if cpu:
            lines += ["", f"Against lama-first's CPU time (load-independent): worst ratio {max(cpu):.2f} — "
                          f"**{'met' if max(cpu) <= 0.2 else 'not met'}**."]
    (args.out / "logistics_hpn_fd.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
