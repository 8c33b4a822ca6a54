"""How much can any batching save on a single-origin problem?  (seed 002 Fig. 3, single regime)

For a generated problem with one origin and one destination, the same map
and vehicles are kept with only the first package, and HPN solves that
one-package problem: its cost splits into the *route* (Travel steps, cost
10 each) and the *per-package* part (Load, Unload, loader work).  A
schedule that carries all n packages together on one trip per leg — the
best batching could do, ignoring cargo capacity and any extra loader
work a full bay needs — costs about ``route + n * per_package``; its
percent decrease against HPN's cost on the full problem bounds what RCHPN
can reach there.  HPN's cost is read from stored reproduction runs
(``nowplan reproduce 002 --runs FILE``), so nothing else is rerun.

    .venv/bin/python benchmarks/marsupial_batch_bound.py \\
        --runs benchmarks/results/marsupial_fig3_runs.jsonl --sizes 3-8 --trials 10
"""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.core.atoms import Goal
from nowplan.core.domain import Problem
from nowplan.core.state import State
from nowplan.domains.marsupial.model import PLANNER
from nowplan.domains.marsupial.problems import generate
from nowplan.domains.marsupial.scenarios import make_episode

log = logging.getLogger("marsupial_batch_bound")


def first_package_only(problem: Problem) -> Problem:
    """The same map, vehicles and first package ``p0``; the other packages removed."""
    drop = {o for o, t in problem.objects.items() if t == "package" and o != "p0"}
    atoms = [a for a in problem.init.atoms() if not (a.args and a.args[0] in drop)]
    goal = Goal.of([a for a in problem.goal.atoms if a.args[0] not in drop], problem.domain.rules)
    objects = {o: t for o, t in problem.objects.items() if o not in drop}
    return Problem(problem.domain, objects, State(atoms), goal, problem.name + "-p0")


def split_cost(regime: str, n: int, trial: int) -> tuple[float, float]:
    """(route, per-package) cost of HPN on the problem's one-package version."""
    problem, spec = generate(regime, n, trial)
    ep = make_episode(first_package_only(problem), spec, trial)
    st = parse_strategy("hpn", max_actions=3000, max_plans=20000, time_limit=120, planner=PLANNER)
    run_episode(ep, st, seed=trial)
    executed = ep.world.asked
    route = sum(a.cost() for a in executed if a.name == "travel")
    return route, sum(a.cost() for a in executed) - route


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=Path, required=True, help="stored runs (reproduce 002 --runs FILE)")
    ap.add_argument("--regime", default="single")
    ap.add_argument("--sizes", default="3-8")
    ap.add_argument("--trials", type=int, default=10)
    args = ap.parse_args()
    lo, _, hi = args.sizes.partition("-")
    sizes = range(int(lo), int(hi or lo) + 1)
    runs = [json.loads(x) for x in args.runs.read_text().splitlines() if x.strip()]
    cost = {(r["packages"], r["trial"], r["strategy"]): r for r in runs if r["regime"] == args.regime}
    print("| packages | problems | HPN cost | RCHPN cost | RCHPN decrease % | batching bound % |")
    print("|---|---|---|---|---|---|")
    for n in sizes:
        rows = []
        for t in range(args.trials):
            h, p = cost.get((n, t, "hpn")), cost.get((n, t, "hpn+peephole"))
            if h is None or p is None or not (h["goal_holds"] and p["goal_holds"]):
                continue
            route, per = split_cost(args.regime, n, t)
            bound = 100.0 * (1 - (route + n * per) / h["cost"])
            rows.append((h["cost"], p["cost"], 100.0 * (1 - p["cost"] / h["cost"]), bound))
        if rows:
            k = len(rows)
            mean = [sum(r[i] for r in rows) / k for i in range(4)]
            print(f"| {n} | {k} | {mean[0]:.0f} | {mean[1]:.0f} | {mean[2]:.1f} | {mean[3]:.1f} |")
        else:
            print(f"| {n} | 0 | – | – | – | – |")


if __name__ == "__main__":
    main()
