"""Print a markdown table from a benchmark CSV: per size and planner, solved runs,
mean planning seconds and mean cost over the solved runs.

    .venv/bin/python benchmarks/summarize.py benchmarks/results/flat_logistics.csv
"""

from __future__ import annotations

import csv
import sys
from collections import defaultdict
from pathlib import Path


def main(path: str) -> int:
    rows = list(csv.DictReader(Path(path).open()))
    planners = list(dict.fromkeys(r["planner"] for r in rows))
    sizes = list(dict.fromkeys((r["cities"], r["locations"], r["airplanes"], r["packages"]) for r in rows))
    cell: dict[tuple[tuple[str, ...], str], list[dict[str, str]]] = defaultdict(list)
    for r in rows:
        cell[((r["cities"], r["locations"], r["airplanes"], r["packages"]), r["planner"])].append(r)
    print("| cities × places, planes, packages | " + " | ".join(planners) + " |")
    print("|---|" + "---|" * len(planners))
    for size in sizes:
        out = []
        for p in planners:
            rs = cell[(size, p)]
            ok = [r for r in rs if r["status"] == "solved"]
            if not ok:
                out.append(f"0/{len(rs)} solved")
                continue
            secs = sum(float(r["seconds"]) for r in ok) / len(ok)
            cost = sum(float(r["cost"]) for r in ok) / len(ok)
            out.append(f"{len(ok)}/{len(rs)}: {secs:.2f} s, cost {cost:.1f}")
        c, l, a, n = size
        print(f"| {c}×{l}, {a}, {n} | " + " | ".join(out) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "benchmarks/results/flat_logistics.csv"))
