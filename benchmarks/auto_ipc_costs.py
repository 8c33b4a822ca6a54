"""Auto-HPN's executed cost against flat planning's first plan, per domain, for stored auto_ipc runs.

Reads the ``runs.jsonl`` of one or more ``benchmarks/auto_ipc.py`` runs (named ``LABEL=DIR``) and
prints, as markdown: per domain the ratio of auto-HPN's summed execution cost to flat's summed
first-plan cost over the pairs both solve (and its range over those pairs), the pairs whose cost
changed between the first and the last run, and each run's reached count and CPU ratios (auto-HPN /
flat, medians over the same pairs, each run's own flat figures)::

    python benchmarks/auto_ipc_costs.py before=benchmarks/results/auto_ipc/hidden_costs_before \\
        after=benchmarks/results/auto_ipc/hidden_costs
"""

from __future__ import annotations

import argparse
import json
import statistics
from pathlib import Path
from typing import Any


def load(path: Path) -> dict[str, dict[str, dict[str, Any]]]:
    """pair -> setting (flat, hpn) -> record."""
    out: dict[str, dict[str, dict[str, Any]]] = {}
    for line in (path / "runs.jsonl").read_text().splitlines():
        r = json.loads(line)
        out.setdefault(r["pair"], {})[r["setting"]] = r
    return out


def both(rec: dict[str, dict[str, Any]]) -> bool:
    f, h = rec.get("flat", {}), rec.get("hpn", {})
    return f.get("outcome") == "solved" and h.get("outcome") == "reached" and "cost" in f and "cost" in h


def domain(pair: str) -> str:
    return pair.rsplit("/", 1)[0]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+", help="LABEL=DIR of a benchmarks/auto_ipc.py run")
    args = ap.parse_args()
    runs = [(s.split("=", 1)[0], load(Path(s.split("=", 1)[1]))) for s in args.runs]
    labels = [lab for lab, _ in runs]
    pairs = sorted(set.intersection(*(set(r) for _, r in runs)))
    print("| run | pairs | flat solved | auto-HPN reached where flat solved | valid | cost ratio sum(auto)/sum(flat) "
          "| plan CPU / flat, median | proc CPU / flat, median |")
    print("|---|---|---|---|---|---|---|---|")
    for lab, r in runs:
        ok = [p for p in pairs if both(r[p])]
        solved = [p for p in pairs if r[p].get("flat", {}).get("outcome") == "solved"]
        valid = sum(1 for p in ok if str(r[p]["hpn"].get("validation", "")).startswith("valid"))
        cost = sum(r[p]["hpn"]["cost"] for p in ok) / sum(r[p]["flat"]["cost"] for p in ok)
        plan = [r[p]["hpn"]["planning_cpu_s"] / r[p]["flat"]["planning_cpu_s"] for p in ok
                if r[p]["flat"].get("planning_cpu_s")]
        proc = [r[p]["hpn"]["process_cpu_s"] / r[p]["flat"]["process_cpu_s"] for p in ok]
        print(f"| {lab} | {len(pairs)} | {len(solved)} | {len(ok)} | {valid} | {cost:.3f} "
              f"| {statistics.median(plan):.2f} | {statistics.median(proc):.2f} |")
    print()
    print("Per domain, over the pairs both solve in every run: auto-HPN cost / flat cost "
          "(sum over the pairs; min-max over them)")
    print()
    print("| domain | pairs | " + " | ".join(labels) + " |")
    print("|---|---|" + "---|" * len(labels))
    for dom in sorted({domain(p) for p in pairs}):
        ps = [p for p in pairs if domain(p) == dom and all(both(r[p]) for _, r in runs)]
        if not ps:
            continue
        cells = []
        for _, r in runs:
            ratios = [r[p]["hpn"]["cost"] / r[p]["flat"]["cost"] if r[p]["flat"]["cost"] else 1.0 for p in ps]
            tot = sum(r[p]["hpn"]["cost"] for p in ps) / max(1e-9, sum(r[p]["flat"]["cost"] for p in ps))
            cells.append(f"{tot:.2f} ({min(ratios):.2f}-{max(ratios):.2f})")
        print(f"| {dom} | {len(ps)} | " + " | ".join(cells) + " |")
    print()
    first, last = runs[0][1], runs[-1][1]
    print(f"Pairs whose auto-HPN cost differs between {labels[0]} and {labels[-1]} "
          "(flat's first-plan cost of each run; auto-HPN's cost and actions)")
    print()
    print(f"| pair | flat ({labels[0]}) | flat ({labels[-1]}) | auto-HPN {labels[0]} | auto-HPN {labels[-1]} |")
    print("|---|---|---|---|---|")
    for p in pairs:
        a, b = first[p].get("hpn", {}), last[p].get("hpn", {})
        if (a.get("cost"), a.get("outcome")) != (b.get("cost"), b.get("outcome")):
            fa, fb = first[p].get("flat", {}), last[p].get("flat", {})
            print(f"| {p} | {fa.get('cost', fa.get('outcome'))} | {fb.get('cost', fb.get('outcome'))} "
                  f"| {a.get('cost', a.get('outcome'))} ({a.get('actions')}) "
                  f"| {b.get('cost', b.get('outcome'))} ({b.get('actions')}) |")


if __name__ == "__main__":
    main()
