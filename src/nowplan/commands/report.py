"""``nowplan report``: markdown and self-contained HTML report of a run store."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser(
        "report",
        help="write a markdown + HTML report (tables, plots) of the runs in a store",
        description=(
            "Read every run in STORE and write DIR/report.md (with PNG plots beside it) and "
            "DIR/report.html (one self-contained page, plots inlined): outcome counts, "
            "mean ± standard error of the metrics per domain / scenario / strategy, and plots."
        ),
    )
    p.add_argument("store", type=Path, help="SQLite run store written by 'nowplan sweep'")
    p.add_argument("-o", "--out", type=Path, required=True, help="output directory (created if missing)")
    p.add_argument("--title", help="report title (default: from the store's file name)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from nowplan.experiments.report import report_store

    files = report_store(args.store, args.out, args.title)
    print(f"wrote {files.markdown}")
    print(f"wrote {files.html}")
    return 0
