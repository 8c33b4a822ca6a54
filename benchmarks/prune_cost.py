"""What pruning the regression engine's plans (planning/prune.py) costs inside HPN runs of registered domains.

Wraps ``regression._pruned`` with a CPU timer and runs ``hpn`` on ``--seeds`` of one scenario; prints the
calls, their plans' mean length, the pruning's CPU and the runs' planning and whole CPU (ratios within one
process: the machine is shared).

    .venv/bin/python benchmarks/prune_cost.py --domain ferry --scenario ferry --seeds 0-4
"""

from __future__ import annotations

import argparse
import time
from typing import Any

import nowplan.planning.regression as regression
from bench_args import span  # benchmarks/bench_args.py, beside this script
from nowplan.api import parse_strategy, run_episode
from nowplan.domains.registry import get_domain


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--domain", required=True)
    ap.add_argument("--scenario", default=None)
    ap.add_argument("--strategy", default="hpn")
    ap.add_argument("--seeds", default="0-4")
    args = ap.parse_args()
    orig = regression._pruned
    acc = {"cpu": 0.0, "calls": 0, "steps": 0}

    def timed(domain: Any, belief: Any, result: Any) -> Any:
        t = time.process_time()
        out = orig(domain, belief, result)
        acc["cpu"] += time.process_time() - t
        acc["calls"] += 1
        acc["steps"] += len(result.plan)
        return out

    regression._pruned = timed  # type: ignore[assignment]
    spec = get_domain(args.domain)
    scenario = spec.scenario(args.scenario or spec.default_scenario)
    whole = planning = 0.0
    for seed in span(args.seeds):
        c0 = time.process_time()
        m = run_episode(scenario(seed), parse_strategy(args.strategy), seed=seed)
        whole += time.process_time() - c0
        planning += m.planning_cpu_s
    calls = int(acc["calls"])
    print(f"{args.domain} {args.scenario or spec.default_scenario} {args.strategy} seeds {args.seeds}: "
          f"{calls} pruned plans (mean {acc['steps'] / max(calls, 1):.1f} steps), pruning {acc['cpu']:.3f} CPU s, "
          f"planning {planning:.2f} s, whole runs {whole:.2f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
