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
            "By default the quick set runs (minutes on 2 cores; the times per seed are in the README); "
            "--full runs the paper's setting (up to hours). Ends with a markdown table, ours beside "
            "the paper's, with a verdict per figure. "
            "A seed whose domain has not landed says so and exits with code 3."
        ),
    )
    p.add_argument("seed", help="000, 002, 003 or 004")
    size = p.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true",
                      help="the quick set (the default; kept so older commands still run)")
    size.add_argument("--full", action="store_true",
                      help="the paper's setting: many more runs (seed 002: 640 runs, about 4 min on one "
                           "process at bbc8ff6; 004: 400 trials, hours on a shared 2-core machine: use "
                           "--jobs and --runs to resume)")
    p.add_argument("--easy", action="store_true",
                   help="seed 004: the original, easy kitchen problems instead of the hard distribution")
    p.add_argument("--out", type=Path,
                   help="write the report, the verdict table (verdicts.md) and plots into this directory")
    p.add_argument("--jobs", type=int, help="worker processes (default 2)")
    p.add_argument("--sizes", type=_sizes,
                   help="seed 002: package counts, e.g. 3-10 or 3,5,7 (default 3,5; --full 3-10); with --sizes "
                        "or --trials each run has the full setting's 600 CPU-s limit (quick set: 120)")
    p.add_argument("--trials", type=int, help="seed 002: trials per regime and size (default 2; --full 10); "
                                              "seed 004: problems per task (default 3; --full 25)")
    p.add_argument("--runs", type=Path, metavar="FILE",
                   help="seeds 002 and 004: append every finished run to this JSON-lines file and skip the runs "
                        "it already holds (resume an interrupted run, or summarise stored runs)")
    p.add_argument("--stored", action="store_true",
                   help="seeds 002 and 004: run nothing; summarise the runs already in --runs FILE that the "
                        "plan (--full/--sizes/--trials) names (points may then have fewer trials)")
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
    from nowplan.experiments import progress

    loading = progress.starting(f"reproduce {args.seed}")  # importing the domains takes a second or two
    try:
        from nowplan.experiments.reproductions import ReproductionOptions, ReproStatus, registered, reproduce

        registered()
    finally:
        loading.close()
    if args.jobs is not None and args.jobs < 1 or args.trials is not None and args.trials < 1:
        print("nowplan reproduce: --jobs and --trials must be at least 1", file=sys.stderr)
        return 2
    if args.stored and args.runs is None:
        print("nowplan reproduce: --stored needs --runs FILE (the stored runs to summarise)", file=sys.stderr)
        return 2
    from nowplan.experiments.verdicts import markdown_table, tally

    result = reproduce(args.seed, ReproductionOptions(
        quick=not args.full, out_dir=args.out, jobs=args.jobs, sizes=args.sizes, trials=args.trials,
        runs_file=args.runs, stored_only=args.stored, easy=args.easy))
    done = result.status is ReproStatus.DONE
    if args.json:
        print(json.dumps(result.to_json(), indent=2))
    if not done:
        print(f"nowplan reproduce: {result.notes}", file=sys.stderr)
        return NOT_IMPLEMENTED_EXIT
    if not args.json:
        which = ("full" if args.full else "chosen sizes/trials" if args.sizes or args.trials
                 else "quick set; --full for the paper's setting")
        print(f"# {result.title} ({'from stored runs, ' if args.stored else ''}{which})")
        print()
        if result.comparisons:
            print(markdown_table(result.comparisons))
            print()
            print(tally(result.comparisons) + ".")
        else:
            print("(no figure to judge: see the rows with --json)")
        if args.out is None:
            print("Rows, notes on how our setting differs, and plots: add --out DIR (or --json).")
        for path in result.outputs:
            print(f"wrote {path}")
    return 0
