"""Marsupial logistics, flat planners against HPN and RCHPN (seed 002 V-B).

Every instance — the seed's FF instance, then one generated problem per
regime, package count and seed — is exported to flat STRIPS PDDL with
loader-level actions (nowplan.domains.marsupial.flat) and solved under a time
limit by Fast Downward lama-first (and seq-opt-lmcut on instances of at most
--optimal-upto packages) and pyperplan (greedy best-first, h_FF); their plans
are validated with unified-planning.  Our hpn and hpn+peephole solve the
hierarchical instance in the simulated world.  Times are CPU seconds: the
planners' processes (FD's translator and search included), and for ours the
whole run (every plan, the peephole optimizer and the simulation); the limit
is in CPU seconds for everyone (a run of ours that finishes later counts as a
time-out, its cost in "cost if late").  Costs use
our cost model (a walk of the loader costs 1); "cost (PDDL)" charges every
loader step.

Writes marsupial_flat.csv, marsupial_flat.md into --out.  Usage:

    .venv/bin/python benchmarks/marsupial_flat.py [--regimes single] [--sizes 2,3,5]
        [--seeds 0] [--time-limit 60] [--optimal-upto 2] [--out benchmarks/results]
"""

from __future__ import annotations

import argparse
import csv
import logging
import platform
import sys
from pathlib import Path

from nowplan.domains.marsupial.flatcmp import markdown, run_table, speedups
from nowplan.domains.marsupial.problems import REGIMES

OUT = Path(__file__).resolve().parent / "results"
FIELDS = ["instance", "packages", "planner", "status", "time_s", "cost", "pddl_cost", "steps", "valid",
          "cost_over_optimum", "late_cost"]


def _ints(text: str) -> list[int]:
    try:
        return [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise SystemExit(f"marsupial_flat: expected comma-separated integers, got '{text}'") from None


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--regimes", default="single", help=f"comma-separated, of {', '.join(REGIMES)}")
    ap.add_argument("--sizes", default="2,3,5", help="package counts (default 2,3,5)")
    ap.add_argument("--seeds", default="0", help="problem seeds (default 0)")
    ap.add_argument("--time-limit", type=float, default=60.0, help="per planner and instance, s")
    ap.add_argument("--optimal-upto", type=int, default=2, help="run seq-opt-lmcut up to this many packages")
    ap.add_argument("--out", type=Path, default=OUT)
    args = ap.parse_args()
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    for name in ("nowplan.acting", "nowplan.planning"):
        logging.getLogger(name).setLevel(logging.WARNING)
    regimes = [r for r in args.regimes.split(",") if r]
    bad = [r for r in regimes if r not in REGIMES]
    if bad:
        raise SystemExit(f"marsupial_flat: unknown regime(s) {', '.join(bad)}; valid: {', '.join(REGIMES)}")
    rows = run_table(regimes, _ints(args.sizes), _ints(args.seeds), args.time_limit, args.optimal_upto)
    args.out.mkdir(parents=True, exist_ok=True)
    with (args.out / "marsupial_flat.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    ratio_lines = ["| instance | packages | ours | our CPU s | FD lama-first CPU s | FD status | FD / ours |",
                   "|---|---|---|---|---|---|---|"]
    for ours in ("hpn", "hpn+peephole"):
        for s in speedups(rows, ours):
            ratio_lines.append(f"| {s['instance']} | {s['packages']} | {ours} | {s['ours_s']} | {s['theirs_s']} | "
                               f"{s['theirs_status']} | {'≥ ' if s['bound'] != 'exact' else ''}{s['ratio']} |")
    text = (
        f"# Marsupial logistics: flat planners vs HPN/RCHPN\n\n"
        f"`{' '.join(['benchmarks/marsupial_flat.py', *sys.argv[1:]])}` — time limit {args.time_limit:g} s, "
        f"{platform.machine()} python {platform.python_version()}\n\n"
        + markdown(rows) + "\n" + "\n".join(ratio_lines) + "\n"
    )
    (args.out / "marsupial_flat.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
