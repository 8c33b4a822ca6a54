"""Fast Downward's anytime search on the flat exports of small marsupial problems (issue 17, seed 002).

For each generated problem (regime, size, trial = problem seed) the flat STRIPS export
(``nowplan.domains.marsupial.flat``) is solved by Fast Downward ``seq-sat-lama-2011`` (lama-first,
then cost-bounded weighted A* restarts) under a CPU limit; every plan it writes (``sas_plan.1``,
``.2``, ...) is validated with unified-planning and rescored with our cost model
(``flat.rescore``).  One JSON row per problem: the first and the best valid plan's cost.  A plan of
the flat encoding is a plan of our problem with a cost at most that of ours up to the encoding's
differences (docs/marsupial.md), so it is a reference for "a good flat plan", not an optimum.

    .venv/bin/python benchmarks/marsupial_rcost12_flat.py --regime single --sizes 3-6 --trials 0-3 \
        --time-limit 60 --out benchmarks/results/marsupial_rcost12/fd_single.jsonl
"""

from __future__ import annotations

import argparse
import json
import logging
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from nowplan.domains.marsupial.flat import flatten, rescore
from nowplan.domains.marsupial.flatcmp import _child_cpu, _downward, _read_plan
from nowplan.domains.marsupial.problems import generate
from nowplan.experiments.sweep import parse_seeds
from nowplan.io.pddl_write import write_pddl
from nowplan.planning.validate import validate_plan

log = logging.getLogger("marsupial_rcost12_flat")


def split(steps: list[str]) -> dict[str, float]:
    """A flat plan's rescored cost by kind (travel, load/unload, loader work by ``flat.rescore``'s
    rule: a run of one loader's moves is one walk) and the loader's walks, grasps and places."""
    out = {"travel": 0.0, "load_unload": 0.0, "walks": 0.0, "grasps": 0.0, "places": 0.0}
    last_move = None
    for s in steps:
        name, *args = s.strip("()").split()
        base = name.split("-")[0]
        if base == "move":
            out["walks"] += last_move != args[0]
            last_move = args[0]
            continue
        last_move = None
        if base in ("travel", "load", "unload"):
            out["travel" if base == "travel" else "load_unload"] += 10.0
        elif base in ("grasp", "place"):
            out[base + "s"] += 1.0
    out["loader"] = rescore(steps) - out["travel"] - out["load_unload"]
    return out


def anytime(regime: str, n: int, trial: int, limit: float) -> dict[str, Any]:
    exe = _downward()
    if exe is None:
        raise SystemExit("marsupial_rcost12_flat: Fast Downward missing; .venv/bin/pip install -e '.[fd]'")
    problem, _ = generate(regime, n, trial)
    row: dict[str, Any] = {"problem": f"{regime}-{n}", "trial": trial, "limit_cpu_s": limit}
    with tempfile.TemporaryDirectory(prefix="nowplan-rcost12-") as tmp:
        work = Path(tmp)
        dom, prob = write_pddl(flatten(problem), work)
        t0, c0 = time.perf_counter(), _child_cpu()
        subprocess.run([sys.executable, str(exe), "--overall-time-limit", f"{int(limit)}s",
                        "--plan-file", str(work / "sas_plan"), "--alias", "seq-sat-lama-2011",
                        str(dom), str(prob)], capture_output=True, text=True, cwd=work, check=False)
        row.update(cpu_s=round(_child_cpu() - c0, 2), wall_s=round(time.perf_counter() - t0, 2))
        costs, best_steps = [], []
        for i in range(1, 1000):  # FD numbers its plans 1, 2, ...; bounded by the limit's few restarts
            steps = _read_plan(work / f"sas_plan.{i}")
            if not steps:
                break
            ok, msg = validate_plan(dom, prob, steps)
            if not ok:
                log.warning("%s-%d t%d plan %d does not validate: %s", regime, n, trial, i, msg)
                continue
            costs.append(rescore(steps))
            if costs[-1] == min(costs):
                best_steps = steps
    row.update(plans=len(costs), first_cost=costs[0] if costs else None, best_cost=min(costs) if costs else None)
    if best_steps:
        row.update(best_split=split(best_steps))
    return row


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--regime", default="single")
    ap.add_argument("--sizes", default="3-6")
    ap.add_argument("--trials", default="0-3")
    ap.add_argument("--time-limit", type=float, default=60.0, help="FD's CPU limit per problem, s")
    ap.add_argument("--out", type=Path, required=True, help="JSON lines, appended")
    args = ap.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    for n in parse_seeds(args.sizes):
        for t in parse_seeds(args.trials):
            row = anytime(args.regime, n, t, args.time_limit)
            log.info("%s", row)
            with args.out.open("a") as f:
                f.write(json.dumps(row) + "\n")


if __name__ == "__main__":
    main()
