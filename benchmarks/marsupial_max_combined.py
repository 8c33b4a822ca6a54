"""RCHPN's complexity limit (seed 002 Alg. 4, ``MaxComplexity``) against execution cost and CPU time.

For each problem (``regime:packages:trial``) HPN runs once and RCHPN once per
limit on the number of operators combined into one subgoal
(``PeepholeConfig.max_combined``; the library's default is 4).  Prints one
line per problem: HPN's (cost, CPU s) and, per limit, RCHPN's (cost, CPU s,
% cost decrease).

    .venv/bin/python benchmarks/marsupial_max_combined.py --limits 4,6,8 \\
        single:3:0 single:3:1 single:4:0 single:4:1 single:5:1 single:6:0
"""

from __future__ import annotations

import argparse
import logging
from typing import Any

from nowplan.acting import peephole
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode

log = logging.getLogger("marsupial_max_combined")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--limits", default="4,6,8", help="max_combined values, comma-separated")
    ap.add_argument("--limit-s", type=float, default=600.0, help="CPU seconds per run")
    ap.add_argument("problems", nargs="+", help="regime:packages:trial")
    args = ap.parse_args()
    limits = [int(k) for k in args.limits.split(",")]
    for spec in args.problems:
        regime, n, trial = spec.split(":")
        m, cpu, ok = timed_run(episode(regime, int(n), int(trial)), "hpn", int(trial), args.limit_s)
        row: dict[Any, Any] = {"hpn": (m.execution_cost, round(cpu, 1))}
        for k in limits:
            # the peephole switch builds Peephole() with its default config: change that default
            peephole.Peephole.__init__.__defaults__ = (peephole.PeepholeConfig(max_combined=k),)
            mk, cpu_k, ok_k = timed_run(episode(regime, int(n), int(trial)), "hpn+peephole", int(trial),
                                        args.limit_s)
            dec = 100.0 * (1 - mk.execution_cost / m.execution_cost) if ok and ok_k else float("nan")
            row[k] = (mk.execution_cost, round(cpu_k, 1), round(dec, 1))
        print(spec, row, flush=True)


if __name__ == "__main__":
    main()
