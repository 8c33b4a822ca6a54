"""``python -m nowplan.domains.namo.combine RUNS.json ...``: seed 000's table over several reproductions.

Every run of ``nowplan reproduce 000`` is deterministic given its seed, so
reproductions of the same code differ only in their timings; this merges
their ``runs.json`` files run by run, keeping each run's fastest timing
(:func:`~nowplan.domains.namo.reproduction.fastest_of`), and prints the
table and the target checks.
"""

from __future__ import annotations

from collections.abc import Sequence

from nowplan.domains.namo.reproduction import aggregate, comparisons, fastest_of, targets
from nowplan.experiments.verdicts import markdown_table


def main(argv: Sequence[str] | None = None) -> int:
    """The table of several reproductions' ``runs.json`` files, each run timed by its fastest timing."""
    import argparse
    import json
    from pathlib import Path

    ap = argparse.ArgumentParser(prog="python -m nowplan.domains.namo.combine", description=main.__doc__)
    ap.add_argument("runs", nargs="+", type=Path, help="runs.json files written by 'nowplan reproduce 000 --out'")
    args = ap.parse_args(argv)
    rows = aggregate(fastest_of([json.loads(p.read_text(encoding="utf-8")) for p in args.runs]))
    cols = ("domain", "algorithm", "reached", "picks_places", "looks", "moves", "drives", "planning_ratio",
            "time_ratio", "planning_ratio_mean")
    out = ["| " + " | ".join(cols) + " |", "|" + "---|" * len(cols)]
    out += ["| " + " | ".join(str(r.get(c, "")) for c in cols) + " |" for r in rows]
    out += targets(rows)
    out += ["", markdown_table(comparisons(rows))]
    print("\n".join(out))  # the command's output is the table
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
