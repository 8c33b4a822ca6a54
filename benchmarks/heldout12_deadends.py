"""Re-run every greenhouse run of a heldout12 JSONL that ended "no plan for the goal (unsolvable ...)"
with the current code and check the dead end in the world: fewer cans of water left (the tank's level,
the pump's one refill if unused, full cans) than plants not watered - or a pest plant with the
sprayer's charges spent.

    PYTHONPATH=src:examples/greenhouse:benchmarks python benchmarks/heldout12_deadends.py \
        benchmarks/results/heldout12/runs_small-x0.2-n0.2.jsonl > benchmarks/results/heldout12/deadends.jsonl
"""

from __future__ import annotations

import json
import logging
import sys

from nowplan.api import atom, parse_strategy, run_episode

from heldout12 import LEVELS


def main(path: str) -> int:
    from greenhouse_domain.scenarios import episode

    logging.getLogger("nowplan").setLevel(logging.ERROR)
    for line in open(path):
        r = json.loads(line)
        if r["outcome"] != "failed" or "unsolvable" not in r["reason"]:
            continue
        ep = episode(r["seed"], **LEVELS[r["level"]][1])
        m = run_episode(ep, parse_strategy(r["strategy"], max_actions=300, time_limit=20.0), seed=r["seed"])
        w = ep.world.state
        plants = [str(x) for (x, _) in w.facts("spot")]
        dry = [x for x in plants if not w.holds(atom("watered", x))]
        pests = [x for x in plants if not w.holds(atom("clean", x))]
        level = int(str(w.facts("level")[0][0])[1:])
        refill = int(str(w.facts("full_level")[0][0])[1:]) if w.holds(atom("pump_ok")) else 0
        cans = len(w.facts("full"))
        no_water = len(dry) > level + refill + cans
        no_spray = bool(pests) and w.holds(atom("charge", "c0"))
        print(json.dumps({"level": r["level"], "strategy": r["strategy"], "seed": r["seed"], "outcome": m.outcome.value,
                          "reason": m.reason, "dead_end_in_world": no_water or no_spray, "unwatered": dry,
                          "no_water_left": no_water, "pests_no_charge": no_spray}), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1]))
