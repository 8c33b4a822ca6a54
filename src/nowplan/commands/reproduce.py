"""``nowplan reproduce SEED``: reproduce a seed paper's table (where its domain has landed)."""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

# exit code when the reproduction is not available yet (distinct from usage errors, 2)
NOT_IMPLEMENTED_EXIT = 3


def register(sub: Any) -> None:
    from nowplan.experiments.papers import PAPERS

    p = sub.add_parser(
        "reproduce",
        help="reproduce a seed paper's table (000, 002, 003, 004)",
        description=(
            "Run the experiments behind a seed paper's table and compare with the paper's numbers. "
            "Seeds: " + "; ".join(f"{s} = {p.system}" for s, p in sorted(PAPERS.items())) + ". "
            "A seed whose domain has not landed says so and exits with code 3."
        ),
    )
    p.add_argument("seed", help="000, 002, 003 or 004")
    p.add_argument("--quick", action="store_true", help="a small version (a few minutes on 2 cores)")
    p.add_argument("--out", type=Path, help="write a report (ours beside the paper's) into this directory")
    p.add_argument("--jobs", type=int, help="worker processes (default 2)")
    p.add_argument("--sizes", type=_sizes,
                   help="seed 002: package counts, e.g. 3-10 or 3,5,7 (default 3-10; --quick 3,5)")
    p.add_argument("--trials", type=int, help="seed 002: trials per regime and size (default 10; --quick 2)")
    p.add_argument("--runs", type=Path, metavar="FILE",
                   help="seed 002: append every finished run to this JSON-lines file and skip the runs "
                        "it already holds (resume an interrupted run, or summarise stored runs)")
    p.add_argument("--stored", action="store_true",
                   help="seed 002: run nothing; summarise the runs already in --runs FILE that the "
                        "plan (--quick/--sizes/--trials) names (points may then have fewer trials)")
    p.add_argument("--json", action="store_true",
                   help='print one JSON document {"seed", "rows", "paper", "notes", …}')
    p.set_defaults(func=main)


def _sizes(text: str) -> tuple[int, ...]:
    """``3-10`` or ``3,5,7``."""
    try:
        if "-" in text:
            lo, hi = (int(x) for x in text.split("-", 1))
            out = tuple(range(lo, hi + 1))
        else:
            out = tuple(int(x) for x in text.split(","))
    except ValueError:
        out = ()
    if not out or min(out) < 1:
        raise argparse.ArgumentTypeError(f"--sizes {text!r}: give a range like 3-10 or a list like 3,5,7")
    return out


def main(args: argparse.Namespace) -> int:
    from nowplan.experiments.reproductions import ReproductionOptions, ReproStatus, reproduce

    if args.jobs is not None and args.jobs < 1 or args.trials is not None and args.trials < 1:
        print("nowplan reproduce: --jobs and --trials must be at least 1", file=sys.stderr)
        return 2
    if args.stored and args.runs is None:
        print("nowplan reproduce: --stored needs --runs FILE (the stored runs to summarise)", file=sys.stderr)
        return 2
    result = reproduce(args.seed, ReproductionOptions(
        quick=args.quick, out_dir=args.out, jobs=args.jobs, sizes=args.sizes, trials=args.trials,
        runs_file=args.runs, stored_only=args.stored))
    done = result.status is ReproStatus.DONE
    if args.json:
        print(json.dumps(result.to_json(), indent=2))
    if not done:
        print(f"nowplan reproduce: {result.notes}", file=sys.stderr)
        return NOT_IMPLEMENTED_EXIT
    if not args.json:
        print(result.title)
        for row in result.rows:
            print("  " + ", ".join(f"{k}={v}" for k, v in row.items()))
        if result.notes:
            print(result.notes)
        for path in result.outputs:
            print(f"wrote {path}")
    return 0
