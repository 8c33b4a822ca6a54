"""Seed 000's runs, one by one: planner calls, their CPU time, replans and why (issue 17's diagnosis).

For each (algorithm, seed) of a NAMO scenario, runs the reproduction's
strategy (the same planner, budget and settings as ``nowplan reproduce
000``) and prints the number of planner calls, their summed and mean CPU
time, the two dearest calls, the replans and picks/places/moves; with
``--why`` also every reconsideration's reason and the stage-2 comparisons
(gain, fog spread and the threshold, from the triggers' debug log).

    python benchmarks/namo_planner_calls.py --scenario domain2 --seeds 0-9
    python benchmarks/namo_planner_calls.py --scenario domain2 --seeds 0 --why --params '{"reconsider_sd": 0}'
"""

from __future__ import annotations

import argparse
import json
import logging
from dataclasses import fields, replace
from typing import Any

from nowplan.experiments.sweep import parse_seeds


def main(argv: list[str] | None = None) -> int:
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.namo.params import Params
    from nowplan.domains.namo.reproduction import ALGORITHMS, PLANNER, SETTINGS
    from nowplan.domains.namo.scenarios import SCENARIOS, episode
    from nowplan.trace import Trace

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--scenario", default="domain2")
    ap.add_argument("--seeds", default="0-9")
    ap.add_argument("--algorithms", default="original BHPN,selective replanning",
                    help=f"comma-separated, of: {', '.join(ALGORITHMS)}")
    ap.add_argument("--params", default="{}", help='JSON object of Params fields, e.g. \'{"reconsider_sd": 0}\'')
    ap.add_argument("--why", action="store_true", help="print reconsiderations and stage-2 comparisons")
    args = ap.parse_args(argv)
    over: dict[str, Any] = json.loads(args.params)
    known = {f.name for f in fields(Params)}
    if not isinstance(over, dict) or set(over) - known:
        ap.error(f"--params: unknown field(s); Params has {sorted(known)}")
    if args.why:
        logging.basicConfig(level=logging.WARNING, format="      %(message)s")
        for name in ("nowplan.domains.namo.triggers", "nowplan.domains.namo.fogcost"):
            logging.getLogger(name).setLevel(logging.DEBUG)
    algs = [a.strip() for a in args.algorithms.split(",")]
    bad = [a for a in algs if a not in ALGORITHMS]
    if bad:
        ap.error(f"--algorithms: unknown {bad}; known: {list(ALGORITHMS)}")
    for alg in algs:
        calls, cpu, replans = 0, 0.0, 0
        for seed in parse_seeds(args.seeds):
            scen = SCENARIOS.spec(args.scenario)
            scen = replace(scen, params=replace(scen.params, **over))
            ep = episode(scen, seed)
            st = parse_strategy(ALGORITHMS[alg], max_actions=scen.max_actions, max_plans=800, time_limit=240.0)
            st = replace(st, planner=replace(PLANNER, seed=seed), **SETTINGS.get(alg, {}))
            tr = Trace()
            m = run_episode(ep, st, seed=seed, trace=tr)
            plans = [e for e in tr.events if e["event"] in ("plan", "plan_failed")]
            t = sum(float(e.get("cpu_s", 0.0)) for e in plans)
            reps = [e for e in tr.events if e["event"] == "replan"]
            dear = sorted((float(e.get("cpu_s", 0.0)) for e in plans), reverse=True)[:2]
            c = m.action_counts
            print(f"{alg} seed {seed}: {m.outcome.value}, {len(plans)} planner calls, {t:.3f} s "
                  f"({1000 * t / max(1, len(plans)):.1f} ms/call; dearest {', '.join(f'{x:.3f}' for x in dear)}), "
                  f"{len(reps)} replans, picks/places {c['Pick'] + c['Place']}, moves {c['Move']}")
            if args.why:
                for e in reps:
                    print(f"      replan ({e['trigger']}): {e['reason']}")
            calls, cpu, replans = calls + len(plans), cpu + t, replans + len(reps)
        print(f"{alg}: {calls} planner calls, {cpu:.3f} s, {1000 * cpu / max(1, calls):.2f} ms/call, {replans} replans")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
