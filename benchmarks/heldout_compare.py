"""Compare two held-out benchmark runs (JSONL rows of ``benchmarks/heldout_runs.py``) run by run.

For the (level, strategy, seed) runs present in both files: how many reached in each, how many have
the same outcome and the same number of actions, and every run whose outcome differs.

    python benchmarks/heldout_compare.py BEFORE.jsonl AFTER.jsonl
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

Key = tuple[str, str, int]


def load(path: Path) -> dict[Key, dict[str, Any]]:
    rows: dict[Key, dict[str, Any]] = {}
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.strip():
            r = json.loads(line)
            rows[(str(r.get("level")), str(r.get("strategy")), int(r.get("seed", -1)))] = r
    return rows


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    before, after = load(Path(argv[0])), load(Path(argv[1]))
    keys = sorted(set(before) & set(after))
    reached = [sum(rows[k].get("outcome") == "reached" for k in keys) for rows in (before, after)]
    same = sum(before[k].get("outcome") == after[k].get("outcome")
               and before[k].get("actions") == after[k].get("actions") for k in keys)
    print(f"{len(keys)} runs in both; reached: before {reached[0]}, after {reached[1]}; "
          f"same outcome and number of actions: {same}")
    for k in keys:
        b, a = before[k], after[k]
        if b.get("outcome") != a.get("outcome"):
            print(f"  {k}: {b.get('outcome')} ({b.get('actions')} actions) -> {a.get('outcome')} "
                  f"({a.get('actions')} actions) {str(a.get('reason') or '')[:120]}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
