"""The first flat planner call of a registered scenario under each estimate and weight (the `flat` retry).

One regression call for the scenario's whole goal from its initial belief, with the planner settings
of ``parse_strategy("flat")`` (the domain's own as base) but HPN's shortcuts and the retry off, for
every heuristic x weight: status, nodes expanded, plan length and cost, CPU seconds.  Why
``PlannerConfig.retry_weight`` is 5 under `flat` (benchmarks/results/retry_1cf3f9a/):

    PYTHONPATH=examples/greenhouse NOWPLAN_DOMAINS=greenhouse_domain \
        .venv/bin/python benchmarks/flat_weights.py --domain greenhouse --scenario tend --seed 0
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace

from nowplan.acting.strategy import parse_strategy
from nowplan.core.levels import flat_levels
from nowplan.domains.registry import get_domain
from nowplan.planning.regression import plan


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--domain", required=True)
    ap.add_argument("--scenario", default="")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--max-nodes", type=int, default=50_000)
    ap.add_argument("--heuristics", default="hadd,hff,hmax")
    ap.add_argument("--weights", default="1,2,5")
    args = ap.parse_args(argv)
    spec = get_domain(args.domain)
    ep = spec.scenario(args.scenario or spec.default_scenario)(args.seed)
    p = ep.problem
    base = parse_strategy("flat", base_planner=spec.planner).planner
    print(f"{args.domain} {args.scenario or spec.default_scenario} seed {args.seed}: goal {p.goal}")
    print("| heuristic | weight | status | expanded | length | cost | CPU s |")
    print("|---|---|---|---|---|---|---|")
    for h in args.heuristics.split(","):
        for w in (float(x) for x in args.weights.split(",")):
            cfg = replace(base, heuristic=h, weight=w, retry_weight=0.0, serialization=False, monotonic=False,
                          max_nodes=args.max_nodes, clock="cpu", time_limit=600.0)
            c0 = time.process_time()
            r = plan(p.domain, p.objects, ep.belief, p.goal, flat_levels(), cfg)
            cpu = time.process_time() - c0
            n = len(r.plan) if r.plan is not None else "-"
            cost = f"{r.plan.cost(ep.belief):.1f}" if r.plan is not None else "-"
            print(f"| {h} | {w:g} | {r.status.name.lower()} | {r.expanded} | {n} | {cost} | {cpu:.2f} |", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
