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
    p.add_argument("--json", action="store_true",
                   help='print one JSON document {"seed", "rows", "paper", "notes", …}')
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from nowplan.experiments.reproductions import ReproductionOptions, ReproStatus, reproduce

    result = reproduce(args.seed, ReproductionOptions(quick=args.quick, out_dir=args.out))
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
