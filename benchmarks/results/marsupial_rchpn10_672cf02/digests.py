"""Compare the executed-action digests of two `benchmarks/rchpn_split.py --out` files, run by run.

    python digests.py rchpn_split_both_main_a6d7008.jsonl rchpn_split_both_672cf02.jsonl
"""
import json
import sys


def load(path):
    return {(r["problem"], r["trial"], r["strategy"]): r for r in map(json.loads, open(path))}


a, b = load(sys.argv[1]), load(sys.argv[2])
both = [k for k in a if k in b]
print(f"same executed actions: {sum(a[k]['actions'] == b[k]['actions'] for k in both)} of {len(both)} runs")
for k in both:
    if a[k]["actions"] != b[k]["actions"]:
        print("differs:", k, a[k]["cost"], "->", b[k]["cost"])
