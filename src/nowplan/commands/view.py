"""``nowplan view``: one self-contained HTML page for a JSONL trace."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any


def register(sub: Any) -> None:
    p = sub.add_parser(
        "view",
        help="write a self-contained HTML page showing a trace's plan tree and timeline",
        description=(
            "Read a JSONL trace (nowplan run --trace FILE) and write one HTML page with no external "
            "resources: the planning-and-execution tree (plans, goals, operators, levels, executed "
            "steps, pops and replans), a timeline of actions and observations, and any frames."
        ),
    )
    p.add_argument("trace", type=Path, help="JSONL trace file")
    p.add_argument("-o", "--out", type=Path, help="output page (default: TRACE with .html)")
    p.add_argument("--title", help="page title (default: from the trace's file name)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from nowplan.viz.viewer import write_viewer

    out = args.out or args.trace.with_suffix(".html")
    path = write_viewer(args.trace, out, args.title)
    print(f"wrote {path}")
    return 0
