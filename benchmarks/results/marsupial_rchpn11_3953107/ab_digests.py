"""Compare the before/after rows of a `benchmarks/marsupial_ab.py --out` file, run by run.

    python ab_digests.py marsupial_ab_all_3953107.jsonl
"""
import json
import sys

by = {}
for r in map(json.loads, open(sys.argv[1])):
    by.setdefault((r["problem"], r["trial"], r["strategy"]), {})[r["tag"]] = r
pairs = {k: v for k, v in by.items() if len(v) == 2}
same = [k for k, v in pairs.items() if v["before"]["actions"] == v["after"]["actions"] and v["before"]["cost"] == v["after"]["cost"]]
print(f"same executed actions and cost: {len(same)} of {len(pairs)} runs")
for k, v in sorted(pairs.items()):
    if k not in same:
        print("differs:", k, v["before"]["cost"], "->", v["after"]["cost"])
