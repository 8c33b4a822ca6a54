"""The ``regroup`` switch on hand-written hierarchies: ``hpn`` against ``hpn+regroup`` (planning/regroup.py).

Each run is ``nowplan run --domain D --scenario S --strategy X --seed K --json`` in a fresh process, as
a user runs it; one JSON line per run (domain, scenario, strategy, seed, outcome, actions, execution
cost, planning CPU s) goes to ``--out``, and a table of means per (domain, scenario) and strategy is
printed.  ``--criticality auto`` PDDL runs regroup by default; this measures what the switch does where
a domain's author wrote the hierarchy.

    .venv/bin/python benchmarks/regroup_ab.py --seeds 0-4 --out benchmarks/results/regroup_HASH/registered.jsonl
    .venv/bin/python benchmarks/regroup_ab.py --summarize benchmarks/results/regroup_HASH/registered.jsonl

The other held-out examples (``--cases``, ``--strategies``):

    PYTHONPATH=examples/drone:examples/greenhouse:... NOWPLAN_DOMAINS=drone_domain,greenhouse_domain,... \
        .venv/bin/python benchmarks/regroup_ab.py --cases drone:deliver,greenhouse:tend --strategies hpn,hpn+noprune,hpn+regroup

``--compare-csv BEFORE AFTER`` compares two ``benchmarks/criticality_auto.py`` runs (e.g. ``--auto-strategy
hpn+refine-flat+noregroup`` against the default): per domain, the auto runs whose cost fell, rose or stayed,
the cost sums beside flat planning's, and any change of outcome.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from collections import defaultdict
from pathlib import Path
from typing import Any

from bench_args import span  # benchmarks/bench_args.py, beside this script

CASES = [("logistics", "medium"), ("logistics", "large"), ("marsupial", "single-5"), ("marsupial", "both-5"),
         ("ferry", "ferry"), ("millshop", "shop"), ("tidy", "tidy"), ("mine", "dig")]
STRATEGIES = ["hpn", "hpn+regroup"]
NOWPLAN = Path(sys.executable).with_name("nowplan")


def run(domain: str, scenario: str, strategy: str, seed: int) -> dict[str, Any]:
    cmd = [str(NOWPLAN), "run", "--domain", domain, "--scenario", scenario, "--strategy", strategy,
           "--seed", str(seed), "--json"]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    row: dict[str, Any] = {"domain": domain, "scenario": scenario, "strategy": strategy, "seed": seed}
    if p.returncode not in (0, 1) or not p.stdout.strip():
        row.update(outcome="error", error=(p.stderr.strip().splitlines() or [""])[-1])
        return row
    d = json.loads(p.stdout)
    row.update(outcome=d["outcome"], actions=d["actions"], cost=d["execution_cost"],
               planning_cpu_s=round(d["planning_cpu_s"], 4))
    return row


def summarize(rows: list[dict[str, Any]]) -> None:
    by: dict[tuple[str, str], dict[str, list[dict[str, Any]]]] = defaultdict(lambda: defaultdict(list))
    for r in rows:
        by[(r["domain"], r["scenario"])][r["strategy"]].append(r)
    print("| domain | scenario | strategy | reached | mean actions | mean cost | mean planning CPU s |")
    print("|---|---|---|---|---|---|---|")
    for (d, s), per in by.items():
        for strat, rs in per.items():
            ok = [r for r in rs if r["outcome"] == "reached"]
            mean = (lambda k: sum(r[k] for r in ok) / len(ok)) if ok else (lambda k: float("nan"))
            print(f"| {d} | {s} | {strat} | {len(ok)}/{len(rs)} | {mean('actions'):.1f} | {mean('cost'):.1f} | "
                  f"{mean('planning_cpu_s'):.3f} |")


def compare_csv(before: Path, after: Path) -> None:
    import csv

    def load(p: Path) -> dict[tuple[str, ...], dict[str, str]]:
        with p.open() as fh:
            return {(r["suite"], r["domain"], r["instance"], r["setting"]): r for r in csv.DictReader(fh)}

    a, b = load(before), load(after)
    per: dict[str, list[float]] = defaultdict(lambda: [0, 0, 0, 0.0, 0.0, 0.0])
    changed = []
    for k, rb in sorted(b.items()):
        ra = a.get(k)
        if k[3] != "auto" or ra is None:
            continue
        if ra["outcome"] != rb["outcome"]:
            changed.append(f"{k[1]} {k[2]}: {ra['outcome']} -> {rb['outcome']}")
        flat = b.get((k[0], k[1], k[2], "flat"))
        if ra["outcome"] != "reached" or rb["outcome"] != "reached" or flat is None or flat["outcome"] != "reached":
            continue
        ca, cb = float(ra["cost"]), float(rb["cost"])
        d = per[k[1]]
        d[0 if cb < ca else 1 if cb > ca else 2] += 1
        d[3], d[4], d[5] = d[3] + ca, d[4] + cb, d[5] + float(flat["cost"])
    print(f"before: {before}\nafter:  {after}\n")
    print("| domain | cost fell | rose | same | cost sum before | after | flat |")
    print("|---|---|---|---|---|---|---|")
    tot = [0.0] * 6
    for dn, d in sorted(per.items()):
        print(f"| {dn} | {d[0]:.0f} | {d[1]:.0f} | {d[2]:.0f} | {d[3]:g} | {d[4]:g} | {d[5]:g} |")
        tot = [x + y for x, y in zip(tot, d, strict=True)]
    print(f"| all | {tot[0]:.0f} | {tot[1]:.0f} | {tot[2]:.0f} | {tot[3]:g} | {tot[4]:g} | {tot[5]:g} |")
    print("\n(instances that flat planning and both auto runs solve)")
    print("outcomes changed: " + ("; ".join(changed) if changed else "none"))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seeds", default="0-4")
    ap.add_argument("--cases", default="", help="domain:scenario,... instead of the built-in list (an example "
                    "under examples/ is found as a user's plugin: PYTHONPATH and NOWPLAN_DOMAINS)")
    ap.add_argument("--strategies", default=",".join(STRATEGIES))
    ap.add_argument("--out", type=Path, default=None)
    ap.add_argument("--summarize", type=Path, default=None, help="print the table of a stored run and stop")
    ap.add_argument("--compare-csv", type=Path, nargs=2, default=None, metavar=("BEFORE", "AFTER"),
                    help="compare two criticality_auto.py CSVs (auto costs and outcomes) and stop")
    args = ap.parse_args()
    if args.compare_csv is not None:
        compare_csv(*args.compare_csv)
        return 0
    if args.summarize is not None:
        summarize([json.loads(x) for x in args.summarize.read_text().splitlines() if x.strip()])
        return 0
    rows = []
    cases = [tuple(c.split(":", 1)) for c in args.cases.split(",") if c] or CASES
    for domain, scenario in cases:
        for seed in span(args.seeds):
            for strategy in args.strategies.split(","):
                row = run(domain, scenario, strategy, seed)
                rows.append(row)
                print(json.dumps(row), flush=True)
                if args.out is not None:
                    args.out.parent.mkdir(parents=True, exist_ok=True)
                    with args.out.open("a") as fh:
                        fh.write(json.dumps(row) + "\n")
    summarize(rows)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
