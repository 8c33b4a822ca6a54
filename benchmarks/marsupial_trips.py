"""Where RCHPN's cost goes on marsupial problems: vehicle trips and loader work (seed 002, issue 17).

For each problem it runs HPN and RCHPN (``nowplan.domains.marsupial.repro.run_one``'s settings) and
splits the executed cost into Travel, Load/Unload and loader work (the loader operators after a Load
and before the next vehicle operator count for loading, the others for unloading), and counts per
vehicle the *batches* (loads between two of its travels) against a capacity bound that ignores the
bay's geometry: ceil(cells of the packages it carried / (storage cells - 2)).  The packages per batch
show where the complexity limit (``PeepholeConfig.max_combined``) or the order of the legs splits
trips.

    .venv/bin/python benchmarks/marsupial_trips.py --regime single --sizes 6,8,10 --trials 0-2
"""

from __future__ import annotations

import argparse
import math
from collections import defaultdict
from typing import Any

from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.grid import SHAPES
from nowplan.domains.marsupial.problems import generate
from nowplan.domains.marsupial.scenarios import episode
from nowplan.experiments.sweep import parse_seeds


def breakdown(regime: str, n: int, trial: int, strategy: str) -> dict[str, Any]:
    ep = episode(regime, n, trial)
    _, spec = generate(regime, n, trial)
    shapes = dict(ep.belief.facts("shape"))
    _, cpu, ok = timed_run(ep, strategy, trial, 600.0)
    executed = ep.world.asked
    load_work = unload_work = pending = 0.0
    last = None
    batches: dict[str, list[list[str]]] = defaultdict(list)
    moved: dict[str, bool] = {}
    for a in executed:
        if a.name.startswith("loader"):
            pending += a.cost()
            continue
        if a.name not in ("load", "unload", "travel"):
            continue
        if last == "load" or a.name != "unload":
            load_work += pending
        else:
            unload_work += pending
        pending, last = 0.0, a.name
        veh = str(a.args[0] if a.name == "travel" else a.args[1])
        if a.name == "travel":
            moved[veh] = True
        elif a.name == "load":
            if moved.get(veh, True) or not batches[veh]:
                batches[veh].append([])
            moved[veh] = False
            batches[veh][-1].append(str(a.args[0]))
    load_work += pending
    trips = {}
    for veh, bs in sorted(batches.items()):
        rows, cols = spec.bays[veh]
        cells = sum(len(SHAPES[str(shapes[p])]) for b in bs for p in b)
        trips[veh] = (len(bs), math.ceil(cells / (rows * (cols - 2) - 2)), [len(b) for b in bs])
    return {"cost": sum(a.cost() for a in executed), "reached": ok, "cpu": cpu,
            "travel": sum(a.cost() for a in executed if a.name == "travel"),
            "load_unload": sum(a.cost() for a in executed if a.name in ("load", "unload")),
            "loader_load": load_work, "loader_unload": unload_work, "trips": trips}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--regime", default="single")
    ap.add_argument("--sizes", default="6,8,10")
    ap.add_argument("--trials", default="0-2")
    args = ap.parse_args()
    print("| problem | strategy | cost | travel | load+unload | loader (loading / unloading) "
          "| batches per vehicle / capacity bound [packages per batch] |")
    print("|---|---|---|---|---|---|---|")
    for n in parse_seeds(args.sizes):
        for t in parse_seeds(args.trials):
            for strategy in ("hpn", "hpn+peephole"):
                r = breakdown(args.regime, n, t, strategy)
                trips = "; ".join(f"{v} {b}/{lb} {g}" for v, (b, lb, g) in r["trips"].items())
                print(f"| {args.regime}-{n} t{t} | {strategy} | {r['cost']:g}{'' if r['reached'] else ' (failed)'} "
                      f"| {r['travel']:g} | {r['load_unload']:g} | {r['loader_load']:g} / {r['loader_unload']:g} "
                      f"| {trips} |", flush=True)


if __name__ == "__main__":
    main()
