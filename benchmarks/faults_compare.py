"""Compare fault-benchmark runs side by side: ``faults.csv`` files written by ``benchmarks/faults.py``.

For each (faults, strategy) group present in any file: runs reached, mean actions of the reached runs,
planning CPU summed over the group, and the runs that did not reach the goal with their reason.

    python benchmarks/faults_compare.py NAME=PATH/faults.csv NAME=PATH/faults.csv ...
"""

from __future__ import annotations

import csv
import sys
from collections import defaultdict
from pathlib import Path


def main(argv: list[str]) -> int:
    if not argv or any("=" not in a for a in argv):
        print(__doc__, file=sys.stderr)
        return 2
    named = [a.split("=", 1) for a in argv]
    groups: dict[tuple[str, str], dict[str, list[dict[str, str]]]] = defaultdict(lambda: defaultdict(list))
    for name, path in named:
        for r in csv.DictReader(Path(path).open(encoding="utf-8")):
            groups[(r["faults"], r["strategy"])][name].append(r)
    names = [n for n, _ in named]
    print("| faults | strategy | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    misses: list[str] = []
    for (faults, strategy), by in sorted(groups.items()):
        cells = []
        for n in names:
            rs = by.get(n, [])
            if not rs:
                cells.append("–")
                continue
            ok = [r for r in rs if r["outcome"] == "reached"]
            acts = sum(int(r["actions"]) for r in ok) / max(1, len(ok))
            cpu = sum(float(r["planning_cpu_s"] or 0) for r in rs)
            cells.append(f"{len(ok)}/{len(rs)}, {acts:.1f} actions, {cpu:.1f} CPU s")
            misses += [f"- {n}: {faults} {strategy} seed {r['seed']}: {r['outcome']} ({r['reason'][:110]}), "
                       f"{float(r['planning_cpu_s'] or 0):.1f} CPU s, {float(r['wall_s']):.0f} s wall"
                       for r in rs if r["outcome"] != "reached"]
        print(f"| {faults} | {strategy} | " + " | ".join(cells) + " |")
    if misses:
        print("\nNot reached:\n")
        print("\n".join(misses))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
