"""Fault benchmark (issue 14): domains x strategies x fault levels x seeds, resumable.

Every run is a sweep configuration (``nowplan sweep`` machinery,
:mod:`nowplan.experiments.sweep`) whose scenario carries its fault level
(``small?failure=0.5``, :mod:`nowplan.experiments.faults`), so runs are
stored in an SQLite store as they finish and an interrupted benchmark resumes
by running the same command again.  At the end (and with ``--summarize``)
the store is exported to ``faults.csv`` (one row per run) and ``faults.md``
(success %, mean actions, cost and planning CPU per domain x level x
strategy, and the reason of every failure).

    python benchmarks/faults.py --quick            # a few minutes: 2 seeds, the extreme levels, 5 strategies
    python benchmarks/faults.py                    # the full benchmark: seeds 0-19, every level and strategy
    python benchmarks/faults.py --summarize        # only re-export the CSV and the table from the store
    python benchmarks/faults.py --stress           # just beyond the benchmark's range: seeds 0-9, harsher levels

Fault levels (each where the domain's world has the knob; others are left out):
action failure 0.1/0.25/0.5, exogenous change 0.1/0.25/0.5, both at 0.5,
range-dependent sensor noise 0.04/0.08/0.1 m per m, missed detections 0.1/0.3.
``--stress`` levels (results in ``results/faults_stress/``): action failure 0.6/0.7,
exogenous change 0.6, both at 0.6, sensor noise 0.15/0.2 m per m, missed detections
0.4/0.5, failure 0.5 + missed 0.3 + noise 0.1/m together, range-independent sensor
noise 0.03 m, and failure 0.5 + missed 0.3 + noise 0.03 m together (the kitchen's sensor has no
range-dependent noise; ``--domains kitchen`` adds the PyBullet kitchen's cook task).
Strategies: those of ``tests/test_matrix.py`` (every switch on top of hpn or
as the online policy, plus the papers' combinations); a strategy a domain
refuses up front is left out for that domain.
"""

from __future__ import annotations

import argparse
import csv
import logging
import sys
from collections import Counter, defaultdict
from pathlib import Path
from typing import Any

from nowplan.acting.strategy import parse_strategy, strategy_names
from nowplan.domains.registry import get_domain
from nowplan.errors import NowplanError
from nowplan.experiments.faults import Faults, split_scenario, supports
from nowplan.experiments.records import RunRecord
from nowplan.experiments.store import Store
from nowplan.experiments.sweep import SweepSpec, make_backend, parse_seeds, run_sweep

RESULTS = Path(__file__).resolve().parent / "results"
# the scenario each domain is benchmarked on
SCENARIOS = {"logistics": "small", "marsupial": "single-3", "namo": "domain1", "pieces": "tiny-disturbed"}
# domains benchmarked only when named with --domains (slower: PyBullet), and their scenario
EXTRA_SCENARIOS = {"kitchen": "cook"}
ONLINE = ("online", "reuse", "deferred")

FULL_LEVELS = (
    Faults(),
    Faults(failure=0.1), Faults(failure=0.25), Faults(failure=0.5),
    Faults(exogenous=0.1), Faults(exogenous=0.25), Faults(exogenous=0.5),
    Faults(failure=0.5, exogenous=0.5),
    Faults(sigma_per_m=0.04), Faults(sigma_per_m=0.08), Faults(sigma_per_m=0.1),
    Faults(miss=0.1), Faults(miss=0.3),
)
QUICK_LEVELS = (Faults(), Faults(failure=0.5), Faults(exogenous=0.5), Faults(failure=0.5, exogenous=0.5),
                Faults(sigma_per_m=0.1), Faults(miss=0.3))
STRESS_LEVELS = (Faults(failure=0.6), Faults(failure=0.7), Faults(exogenous=0.6), Faults(failure=0.6, exogenous=0.6),
                 Faults(sigma_per_m=0.15), Faults(sigma_per_m=0.2), Faults(miss=0.4), Faults(miss=0.5),
                 Faults(failure=0.5, sigma_per_m=0.1, miss=0.3),
                 Faults(sigma=0.03), Faults(failure=0.5, miss=0.3, sigma=0.03))
QUICK_STRATEGIES = ("hpn", "hpn+flexible", "hpn+aggressive", "hpn+flexible+serendipity+selective+foresight",
                    "online+reuse+deferred")


def matrix_strategies() -> list[str]:
    """The strategies of tests/test_matrix.py."""
    def spec(switch: str) -> str:
        if switch in ("hpn", "flat", "online"):
            return switch
        return f"online+{switch}" if switch in ONLINE else f"hpn+{switch}"

    return sorted({spec(s) for s in strategy_names()}) + [
        "hpn+flexible+serendipity+selective+foresight", "flat+flexible+serendipity", "hpn+peephole+flexible",
        "online+reuse+deferred",
    ]


def refused(domain: str, scenario: str, strategy: str) -> str | None:
    """Why the domain refuses the strategy up front (as a run would, before its first action), or None."""
    from nowplan.acting.run import run_episode

    ep = get_domain(domain).scenario(scenario)(0)
    try:
        run_episode(ep, parse_strategy(strategy, max_actions=0, time_limit=5.0), seed=0)
    except NowplanError as exc:
        return str(exc)
    return None


def levels_for(domain: str, scenario: str, levels: tuple[Faults, ...]) -> list[Faults]:
    ep = get_domain(domain).scenario(scenario)(0)
    return [lv for lv in levels if all(supports(ep, k) for k, _ in lv.items())]


def parse_levels(text: str) -> tuple[Faults, ...]:
    """``'none,exogenous=0.5'`` -> the fault levels (a bad knob is a ScenarioError naming it)."""
    out = []
    for lab in (x.strip() for x in text.split(",")):
        if lab:
            out.append(Faults() if lab == "none" else split_scenario(f"x?{lab}")[1])
    return tuple(out)


def export(records: list[RunRecord], out: Path) -> None:
    """faults.csv (one row per run) and faults.md (the table and every failure's reason)."""
    out.mkdir(parents=True, exist_ok=True)
    rows: list[dict[str, Any]] = []
    for r in sorted(records, key=lambda r: (r.config.domain, r.config.scenario, r.config.strategy, r.config.seed)):
        base, faults = split_scenario(r.config.scenario)
        m = r.metrics
        rows.append({
            "domain": r.config.domain, "scenario": base, "faults": faults.label() or "none",
            "strategy": r.config.strategy, "seed": r.config.seed, "outcome": r.outcome, "reason": r.reason,
            "actions": m.get("actions", ""), "cost": m.get("execution_cost", ""),
            "planning_cpu_s": m.get("planning_cpu_s", ""), "wall_s": round(r.wall_s, 3), "version": r.version,
        })
    with (out / "faults.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]) if rows else ["domain"])
        w.writeheader()
        w.writerows(rows)
    groups: dict[tuple[str, str, str], list[dict[str, Any]]] = defaultdict(list)
    for row in rows:
        groups[(row["domain"], row["faults"], row["strategy"])].append(row)

    def mean(xs: list[Any]) -> str:
        v = [float(x) for x in xs if x != ""]
        return f"{sum(v) / len(v):.3g}" if v else "–"

    lines = ["# Fault benchmark", "", "Made by `benchmarks/faults.py` (see benchmarks/results/README.md for the command).",
             "Success = outcome `reached`; actions, cost and planning CPU s are means over all runs.", "",
             "| domain | faults | strategy | runs | success % | actions | cost | planning CPU s | failures |",
             "|---|---|---|---|---|---|---|---|---|"]
    below: list[str] = []
    for (dom, flt, st), rs in sorted(groups.items()):
        ok = sum(r["outcome"] == "reached" for r in rs)
        pct = 100.0 * ok / len(rs)
        why = Counter(f"{r['outcome']}: {r['reason'][:80]}" for r in rs if r["outcome"] != "reached")
        lines.append(f"| {dom} | {flt} | {st} | {len(rs)} | {pct:.0f} | {mean([r['actions'] for r in rs])} | "
                     f"{mean([r['cost'] for r in rs])} | {mean([r['planning_cpu_s'] for r in rs])} | "
                     f"{len(rs) - ok} |")
        if pct < 95.0:
            below.append(f"{dom} / {flt} / {st}: {ok}/{len(rs)}")
    lines += ["", f"Below 95 % success: {len(below)} of {len(groups)} groups.", ""]
    lines += [f"- {b}" for b in below]
    lines += ["", "## Every failure", "", "| domain | faults | strategy | seed | outcome | reason |", "|---|---|---|---|---|---|"]
    for row in rows:
        if row["outcome"] != "reached":
            reason = str(row["reason"]).replace("|", "/")
            lines.append(f"| {row['domain']} | {row['faults']} | {row['strategy']} | {row['seed']} | "
                         f"{row['outcome']} | {reason} |")
    (out / "faults.md").write_text("\n".join(lines) + "\n")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="2 seeds, the extreme levels, 5 strategies (minutes)")
    ap.add_argument("--stress", action="store_true", help="harsher levels than the benchmark's, seeds 0-9 "
                    "(results/faults_stress, store faults_stress.sqlite)")
    ap.add_argument("--domains", default=",".join(SCENARIOS), help="domains joined by ','")
    ap.add_argument("--strategies", help="strategies joined by ',' (default: the matrix's, or --quick's five)")
    ap.add_argument("--seeds", help="seeds (default 0-19, --quick 0-1)")
    ap.add_argument("--levels", help="fault levels joined by ',', each as in the table's faults column "
                    "(e.g. 'exogenous=0.5,failure=0.5&exogenous=0.5', 'none'); default: every level")
    ap.add_argument("--time-limit", type=float, help="seconds per run (default 60, --quick 30)")
    ap.add_argument("--jobs", type=int, default=1, help="runs at a time (default 1: the machine is shared)")
    ap.add_argument("--store", type=Path, help="SQLite store (default results/faults.sqlite, --quick faults_quick.sqlite)")
    ap.add_argument("--out", type=Path, help="where faults.csv and faults.md go (default benchmarks/results, "
                    "--quick benchmarks/results/faults_quick)")
    ap.add_argument("--summarize", action="store_true", help="only export the store's runs")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
    quick = args.quick
    try:
        default_levels = STRESS_LEVELS if args.stress else QUICK_LEVELS if quick else FULL_LEVELS
        chosen_levels = parse_levels(args.levels) if args.levels else default_levels
    except NowplanError as exc:
        print(f"faults.py: --levels: {exc}", file=sys.stderr)
        return 2
    seeds = parse_seeds(args.seeds or ("0-1" if quick else "0-9" if args.stress else "0-19"))
    limit = args.time_limit or (30.0 if quick else 60.0)
    tag = "faults_quick" if quick else "faults_stress" if args.stress else ""
    out = args.out or (RESULTS / tag if tag else RESULTS)
    store_path = args.store or (RESULTS / f"{tag or 'faults'}.sqlite")
    store = Store(store_path)
    domains = [d.strip() for d in args.domains.split(",") if d.strip()]
    wanted_keys: set[str] = set()
    backend = make_backend("local", args.jobs)
    for dom in domains:
        scen = SCENARIOS.get(dom) or EXTRA_SCENARIOS.get(dom) or get_domain(dom).default_scenario
        levels = levels_for(dom, scen, chosen_levels)
        names = args.strategies.split(",") if args.strategies else list(QUICK_STRATEGIES if quick else matrix_strategies())
        strategies = []
        for st in names:
            why = refused(dom, scen, st)
            if why is None:
                strategies.append(st)
            else:
                print(f"{dom}: {st} left out (refused: {why[:100]})", file=sys.stderr)
        spec = SweepSpec(dom, tuple(lv.scenario(scen) for lv in levels), tuple(strategies), tuple(seeds), limit)
        wanted_keys |= {c.key for c in spec.configs()}
        if args.summarize:
            continue
        res = run_sweep(spec, store, backend, progress=sys.stderr.isatty())
        print(res.summary())
    records = [r for r in store.records() if r.key in wanted_keys]
    export(records, out)
    print(f"{len(records)} runs exported to {out / 'faults.csv'} and {out / 'faults.md'}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
