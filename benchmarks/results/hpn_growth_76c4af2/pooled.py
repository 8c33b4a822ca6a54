"""Pooled growth fit over every run in growth.jsonl: least squares on log-log of the per-size mean plan CPU.

    python benchmarks/results/hpn_growth_76c4af2/pooled.py
"""
import collections
import json
import math
from pathlib import Path

rows = [json.loads(line) for line in (Path(__file__).parent / "growth.jsonl").open()]


def slope(xs: list[float], ys: list[float]) -> float:
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


for regime in ("single", "both"):
    by: dict[int, list[float]] = collections.defaultdict(list)
    for r in rows:
        if r["problem"].startswith(regime + "-"):
            by[int(r["problem"].split("-")[1])].append(r["plan_cpu"])
    ns = sorted(by)
    means = [sum(by[n]) / len(by[n]) for n in ns]
    print(f"{regime}: pooled plan CPU n^{slope(ns, means):.2f}; per-size means "
          + ", ".join(f"{n}: {m:.3f} s" for n, m in zip(ns, means)) + f" ({len(by[ns[0]])} runs per size)")
digests = collections.defaultdict(set)
for r in rows:
    digests[(r["problem"], r["trial"])].add((r["actions"], r["cost"]))
print("problems whose actions or cost differ between runs:", sum(len(v) > 1 for v in digests.values()), "of", len(digests))
