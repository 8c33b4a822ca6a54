"""RCHPN against HPN on marsupial problems, for two source trees in one run (before / after).

For every problem (``regime × packages × trial``) it runs ``benchmarks/planner_profile.py`` (HPN
and RCHPN, one JSON line each) first on the ``--before`` tree, then on the ``--after`` tree, so that
both see the same machine load; each row carries the tree's ``--tag``.  The summary compares the
RCHPN/HPN CPU ratios *within* each tree (never absolute seconds: the machine is shared).

    .venv/bin/python benchmarks/marsupial_ab.py --before /tmp/main/src --after src \\
        --regimes both --sizes 3-10 --trials 0-4 --out benchmarks/results/marsupial_both_ab_HASH.jsonl
    .venv/bin/python benchmarks/marsupial_ab.py --summarize benchmarks/results/marsupial_both_ab_HASH.jsonl

``--before`` is typically ``git archive main src | tar -x -C /tmp/main`` with the compiled kernel
copied in.  Times are CPU seconds of the whole run (``time.process_time``).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

from bench_args import span  # benchmarks/bench_args.py, beside this script

HERE = Path(__file__).resolve().parent


def run(args: argparse.Namespace) -> None:
    for trial in span(args.trials):
        for n in span(args.sizes):
            for tag, src in (("before", args.before), ("after", args.after)):
                env = {**os.environ, "PYTHONPATH": str(Path(src).resolve())}
                cmd = [sys.executable, str(HERE / "planner_profile.py"), "--regimes", args.regimes,
                       "--sizes", str(n), "--trials", str(trial), "--no-logistics", "--tag", tag,
                       "--out", str(args.out)]
                subprocess.run(cmd, env=env, check=False, stdout=subprocess.DEVNULL)


def summarize(paths: list[Path]) -> None:
    by: dict[tuple[str, str, str, int], dict[str, dict[str, Any]]] = defaultdict(dict)
    for path in paths:
        for line in path.read_text().splitlines():
            r = json.loads(line)
            if r.get("domain") == "marsupial":
                regime = str(r["problem"]).split("-")[0]
                by[(r.get("tag", ""), regime, r["problem"], int(r["trial"]))][r["strategy"]] = r
    print("| tree | regime | problems | RCHPN unsolved | RCHPN/HPN CPU, ratio of sums (both solved) "
          "| CPU increase, mean of per-problem % (median) | cost decrease % (mean, both solved) |")
    print("|---|---|---|---|---|---|---|")
    for tag in sorted({k[0] for k in by}):
        for regime in sorted({k[1] for k in by if k[0] == tag}):
            keys = [k for k in by if k[0] == tag and k[1] == regime and len(by[k]) == 2]
            bad = [k for k in keys if not by[k]["hpn+peephole"]["goal_holds"]]
            ok = [k for k in keys if k not in bad and by[k]["hpn"]["goal_holds"]]
            h = sum(by[k]["hpn"]["cpu"] for k in ok)
            rc = sum(by[k]["hpn+peephole"]["cpu"] for k in ok)
            inc = [100 * (by[k]["hpn+peephole"]["cpu"] / by[k]["hpn"]["cpu"] - 1) for k in ok]
            dec = [100 * (1 - by[k]["hpn+peephole"]["cost"] / by[k]["hpn"]["cost"]) for k in ok]
            names = ", ".join(f"{k[2]} t{k[3]}" for k in sorted(bad))
            print(f"| {tag} | {regime} | {len(keys)} | {len(bad)}{f' ({names})' if names else ''} | "
                  f"{rc / h:.2f} | {statistics.mean(inc):.0f} ({statistics.median(inc):.0f}) | "
                  f"{statistics.mean(dec):.2f} |")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--before", help="the source tree (a src directory) to compare against")
    ap.add_argument("--after", help="the source tree measured")
    ap.add_argument("--regimes", default="both")
    ap.add_argument("--sizes", default="3-10")
    ap.add_argument("--trials", default="0-4")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--summarize", type=Path, nargs="+", help="print the table from stored rows and stop")
    args = ap.parse_args()
    if args.summarize:
        summarize(args.summarize)
        return 0
    if not (args.before and args.after and args.out):
        ap.error("--before, --after and --out are needed to run (or give --summarize FILE)")
    run(args)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
