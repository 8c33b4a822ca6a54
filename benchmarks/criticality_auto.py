"""Automatic criticalities (issue 18): HPN with ``--criticality auto`` vs hand-written vs flat.

Runs the executive (``nowplan run``'s code, in process, deterministic world)
on every shipped PDDL problem (src/nowplan/data/pddl) and on the classical
benchmark domains (benchmarks/classical: the checked-in p01-p05 and, with
``--larger``, a few larger generated instances; with ``--largest``, instances on which flat planning's
whole run takes at least 1 s), under three settings:

* ``flat``: strategy ``flat`` (one concrete plan, then execution);
* ``auto``: strategy ``hpn+refine-flat`` (``--auto-strategy``) with ``--criticality auto`` and the settings
  ``nowplan run`` adds with it (``commands.run.auto_hierarchy_strategy``: hidden costs, regrouping);
  every planner call uses ``--engine`` (default ``forward``: the executive's
  default regresses at abstract levels, which on barman and depots spends the
  whole budget on the top-level plan before refine-flat plans concretely);
* ``hand``: strategy ``hpn`` with the shipped criticality file, where one exists.

Records per run: outcome, total planning CPU time (every planner call of the
run), the CPU time of ``prepare_problem`` (``auto`` only: deriving the hierarchy,
the reachability statics and the dead-end test, which ground the problem once;
not a planner call, so not in the planning CPU), the total CPU time of the whole run
(``total_cpu_s``: from parsing the PDDL files to the end of the episode, for every
setting: parse, ``prepare_problem``, every planner call, the executive's own work and
the simulated world; grounding caches are cleared before each run, so each starts cold
as a fresh ``nowplan run`` process does), wall time, execution cost,
plans made, planner failures, and the number of levels of the automatic hierarchy.  Writes ``criticality_auto.csv`` and
``criticality_auto.md`` (per-domain summary computed from the CSV) into --out.

    PYTHONPATH=src .venv/bin/python benchmarks/criticality_auto.py [--larger | --larger-only] [--largest | --largest-only]
        [--time-limit 20]
        [--domains gripper,logistics] [--out benchmarks/results/criticality_auto]
"""

from __future__ import annotations

import argparse
import csv
import datetime
import gc
import subprocess
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):  # this checkout's nowplan and benchmarks package
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks.classical.generate import DOMAINS, domain_file, generate, instance_files  # noqa: E402
from nowplan.acting.run import run_episode  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.commands.run import auto_hierarchy_strategy, pddl_action_budget  # noqa: E402
from nowplan.belief.symbolic import SymbolicBelief  # noqa: E402
from nowplan.domains.registry import Episode  # noqa: E402
from nowplan.io.pddl_read import load_pddl  # noqa: E402
from nowplan.planning.problem_hierarchy import prepare_problem  # noqa: E402
from nowplan.planning.task_grounding import clear_cache  # noqa: E402
from nowplan.worlds.symbolic import SymbolicWorld  # noqa: E402

SHIPPED = ROOT / "src" / "nowplan" / "data" / "pddl"
OUT = ROOT / "benchmarks" / "results" / "criticality_auto"
FIELDS = ["suite", "domain", "instance", "setting", "levels", "outcome", "planning_cpu_s", "prep_cpu_s",
          "total_cpu_s", "wall_s",
          "cost", "actions", "plans_made", "plan_failures", "reason"]
# larger instances (parameters, seed) for --larger: where the hierarchy has levels to exploit
LARGER: dict[str, list[tuple[dict[str, int], int]]] = {
    "gripper": [({"balls": 20}, 0), ({"balls": 30}, 0)],
    "logistics": [({"cities": 4, "places": 3, "airplanes": 2, "packages": 12}, 7),
                  ({"cities": 6, "places": 4, "airplanes": 3, "packages": 40}, 7)],
    "miconic": [({"passengers": 10, "floors": 20}, 10), ({"passengers": 30, "floors": 40}, 10)],
    "zenotravel": [({"aircraft": 3, "persons": 10, "cities": 6}, 7), ({"aircraft": 5, "persons": 25, "cities": 10}, 7)],
    "depots": [({"depots": 2, "distributors": 2, "trucks": 2, "crates": 8}, 7),
               ({"depots": 3, "distributors": 3, "trucks": 3, "crates": 16}, 7)],
    "driverlog": [({"drivers": 3, "trucks": 3, "packages": 7, "locations": 8}, 7),
                  ({"drivers": 4, "trucks": 4, "packages": 16, "locations": 14}, 7)],
    "satellite": [({"satellites": 3, "instruments": 2, "modes": 3, "stars": 4, "targets": 8, "images": 8}, 7)],
}
# the largest instances (--largest): sized by the rule "flat planning's whole run takes >= 1 s CPU", with
# flat planning only, before any auto-HPN run on them (benchmarks/results/criticality_auto_sizing)
LARGEST: dict[str, list[tuple[dict[str, int], int]]] = {
    "gripper": [({"balls": 250}, 0), ({"balls": 300}, 0)],
    "logistics": [({"cities": 8, "places": 5, "airplanes": 4, "packages": 40}, 7),
                  ({"cities": 10, "places": 4, "airplanes": 4, "packages": 45}, 7)],
    "miconic": [({"passengers": 150, "floors": 150}, 10), ({"passengers": 200, "floors": 200}, 10)],
    "zenotravel": [({"aircraft": 8, "persons": 50, "cities": 15}, 7), ({"aircraft": 10, "persons": 80, "cities": 20}, 7)],
    "depots": [({"depots": 4, "distributors": 4, "trucks": 4, "crates": 12}, 7),
               ({"depots": 5, "distributors": 5, "trucks": 5, "crates": 15}, 7)],
    "driverlog": [({"drivers": 6, "trucks": 6, "packages": 30, "locations": 20}, 7),
                  ({"drivers": 7, "trucks": 7, "packages": 40, "locations": 25}, 7)],
    "satellite": [({"satellites": 8, "instruments": 3, "modes": 4, "stars": 8, "targets": 50, "images": 50}, 7),
                  ({"satellites": 10, "instruments": 3, "modes": 4, "stars": 10, "targets": 80, "images": 80}, 7)],
}


def run_one(domain: Path, problem: Path, criticality: str | None, strategy: str, limit: float,
            engine: str) -> dict[str, Any]:
    clear_cache()  # every run starts cold, as `nowplan run` does in a fresh process
    gc.collect()
    t_all = time.process_time()
    prob = load_pddl(domain, problem, criticality)
    t_prep = time.process_time()
    if criticality == "auto":
        prob = prepare_problem(prob)  # what `nowplan run --criticality auto` does
    prep = time.process_time() - t_prep  # the hierarchy, reachability statics and dead-end test
    strat = parse_strategy(strategy)
    if criticality == "auto":
        strat = auto_hierarchy_strategy(strat)  # what `nowplan run --criticality auto` adds
    strat = replace(strat, time_limit=limit, planner=replace(strat.planner, engine=engine),  # type: ignore[arg-type]
                    max_actions=pddl_action_budget(prob.objects, strat.max_actions))  # as `nowplan run` does
    episode = Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), str(problem))
    t0 = time.perf_counter()
    m = run_episode(episode, strat, seed=0)
    total = time.process_time() - t_all  # the whole run: parse, set-up, planning, acting, to the goal
    return {
        "levels": prob.domain.top_level + 1,
        "outcome": m.outcome.value,
        "planning_cpu_s": round(m.planning_cpu_s, 4),
        "prep_cpu_s": round(prep, 4),
        "total_cpu_s": round(total, 4),
        "wall_s": round(time.perf_counter() - t0, 4),
        "cost": round(m.execution_cost, 3),
        "actions": m.actions,
        "plans_made": m.plans_made,
        "plan_failures": m.plan_failures,
        "reason": m.reason,
    }


def cases(domains: list[str], larger: bool, tmp: Path,
          largest: bool = False) -> list[tuple[str, str, str, Path, Path, Path | None]]:
    out: list[tuple[str, str, str, Path, Path, Path | None]] = []
    for d in sorted(p.name for p in SHIPPED.iterdir() if p.is_dir()):
        if domains and d not in domains:
            continue
        crit = next(iter(sorted((SHIPPED / d).glob("*.crit"))), None)
        for p in sorted((SHIPPED / d).glob("p[0-9][0-9].pddl")):
            out.append(("shipped", d, p.stem, SHIPPED / d / "domain.pddl", p, crit))
    for d in DOMAINS:
        if domains and d not in domains:
            continue
        for p in instance_files(d):
            out.append(("classical", d, p.stem, domain_file(d), p, None))
        if larger:
            for k, (params, seed) in enumerate(LARGER.get(d, []), start=1):
                path = tmp / f"{d}-large{k}.pddl"
                path.write_text(generate(d, params, seed))
                name = "large-" + "-".join(f"{v}" for v in params.values())
                out.append(("classical", d, name, domain_file(d), path, None))
        if largest:
            for k, (params, seed) in enumerate(LARGEST.get(d, []), start=1):
                path = tmp / f"{d}-largest{k}.pddl"
                path.write_text(generate(d, params, seed))
                name = "largest-" + "-".join(f"{v}" for v in params.values())
                out.append(("classical", d, name, domain_file(d), path, None))
    return out


def summarize(rows: list[dict[str, Any]]) -> str:
    lines = ["| suite | domain | levels | setting | solved | planning CPU s (sum) | wall s (sum) | cost (sum) |",
             "|---|---|---|---|---|---|---|---|"]
    keys = sorted({(r["suite"], r["domain"]) for r in rows})
    for suite, dom in keys:
        mine = [r for r in rows if r["suite"] == suite and r["domain"] == dom]
        insts = sorted({r["instance"] for r in mine})
        levels = max(int(r["levels"]) for r in mine if r["setting"] == "auto")
        for setting in ("flat", "auto", "hand"):
            rs = [r for r in mine if r["setting"] == setting]
            if not rs:
                continue
            ok = [r for r in rs if r["outcome"] == "reached"]
            # sums over instances every setting solved, so the columns compare like with like
            common = [i for i in insts if all(any(r["instance"] == i and r["outcome"] == "reached" for r in mine
                                                  if r["setting"] == s)
                                              for s in {x["setting"] for x in mine})]
            cs = [r for r in rs if r["instance"] in common]
            cpu = sum(float(r["planning_cpu_s"]) for r in cs)
            wall = sum(float(r["wall_s"]) for r in cs)
            cost = sum(float(r["cost"]) for r in cs)
            lines.append(f"| {suite} | {dom} | {levels} | {setting} | {len(ok)}/{len(rs)} | {cpu:.3f} | "
                         f"{wall:.3f} | {cost:g} |")
    return "\n".join(lines)


def tier(instance: str) -> str:
    """The tier of an instance name: ``largest``, ``larger`` or ``base`` (shipped and checked-in problems)."""
    return ("largest" if instance.startswith("largest-") else "larger" if instance.startswith("large-")
            else "base")


def whole_run_counts(rows: list[dict[str, Any]]) -> str:
    """Per tier: on how many instances auto-HPN's whole run (parse to goal) takes less CPU than flat
    planning's (or reaches the goal where flat planning fails), and how many it reaches where flat does."""
    lines = ["| tier | instances | auto reaches where flat does | auto whole run below flat | "
             "hand whole run below flat |", "|---|---|---|---|---|"]
    for t in ("base", "larger", "largest"):
        n = ok = below = 0
        hand_n = hand_below = 0
        for r in rows:
            if r["setting"] != "flat" or tier(r["instance"]) != t:
                continue
            same = [x for x in rows if x["domain"] == r["domain"] and x["instance"] == r["instance"]
                    and x["suite"] == r["suite"]]
            a = next((x for x in same if x["setting"] == "auto"), None)
            if a is None:
                continue
            n += 1
            flat_ok = r["outcome"] == "reached"
            ok += a["outcome"] == "reached" or not flat_ok
            below += a["outcome"] == "reached" and (not flat_ok or float(a["total_cpu_s"]) < float(r["total_cpu_s"]))
            h = next((x for x in same if x["setting"] == "hand"), None)
            if h is not None:
                hand_n += 1
                hand_below += h["outcome"] == "reached" and (
                    not flat_ok or float(h["total_cpu_s"]) < float(r["total_cpu_s"]))
        if n:
            lines.append(f"| {t} | {n} | {ok} of {n} | {below} of {n} | "
                         f"{f'{hand_below} of {hand_n}' if hand_n else '–'} |")
    return "\n".join(lines)


def larger_table(rows: list[dict[str, Any]], prefix: str = "large-") -> str:
    """Issue 18's target on the larger instances: auto-HPN's planning CPU against flat's, instance by
    instance, without and with the CPU of ``prepare_problem`` (the run's set-up under ``--criticality
    auto``; flat planning runs no such set-up: its one planner call grounds the problem itself), and
    the total CPU of each whole run (parse to goal, both settings)."""
    lines = ["| domain | instance | flat (CPU s, cost) | auto (CPU s, cost) | auto / flat CPU | lower? | "
             "auto + prep CPU s | (auto + prep) / flat | lower with prep? | whole run CPU s flat / auto | "
             "auto / flat (whole) | lower whole? |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    n = lower = lower_prep = lower_whole = 0
    for r in rows:
        if r["setting"] != "flat" or not r["instance"].startswith(prefix):
            continue
        a = next((x for x in rows if x["setting"] == "auto" and x["domain"] == r["domain"]
                  and x["instance"] == r["instance"] and x["suite"] == r["suite"]), None)
        if a is None:
            continue
        n += 1

        def cell(x: dict[str, Any]) -> str:
            return (f"{float(x['planning_cpu_s']):.3f}, {float(x['cost']):g}" if x["outcome"] == "reached"
                    else f"{x['outcome']} ({float(x['planning_cpu_s']):.3f} s)")

        fa, fb = float(r["planning_cpu_s"]), float(a["planning_cpu_s"])
        fp = fb + float(a.get("prep_cpu_s") or 0.0)
        ta, tb = float(r.get("total_cpu_s") or 0.0), float(a.get("total_cpu_s") or 0.0)
        reached = a["outcome"] == "reached"
        flat_failed = r["outcome"] != "reached"
        won = reached and (flat_failed or fb < fa)
        won_prep = reached and (flat_failed or fp < fa)
        won_whole = reached and (flat_failed or tb < ta)
        lower += won
        lower_prep += won_prep
        lower_whole += won_whole
        both = not flat_failed and reached and fa > 0
        ratio = f"{fb / fa:.2f}" if both else "–"
        ratio_prep = f"{fp / fa:.2f}" if both else "–"
        ratio_whole = f"{tb / ta:.2f}" if both and ta > 0 else "–"
        lines.append(f"| {r['domain']} | {r['instance']} | {cell(r)} | {cell(a)} | {ratio} | "
                     f"{'yes' if won else 'no'} | {fp:.3f} | {ratio_prep} | {'yes' if won_prep else 'no'} | "
                     f"{ta:.3f} / {tb:.3f} | {ratio_whole} | {'yes' if won_whole else 'no'} |")
    lines += ["", f"auto-HPN reaches the goal with less planning CPU than flat planning (or where flat fails) "
                  f"on {lower} of {n} larger instances, on {lower_prep} of {n} counting its set-up "
                  f"(prepare_problem) too, and with less CPU for the whole run (parse to goal, both "
                  f"settings) on {lower_whole} of {n} ({prefix}* instances); the target (issue 18) asks for all of them."]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--domains", default="", help="comma-separated domain names (default: all)")
    ap.add_argument("--larger", action="store_true", help="add the larger generated instances (LARGER)")
    ap.add_argument("--larger-only", action="store_true",
                    help="only the larger generated instances (implies --larger)")
    ap.add_argument("--largest", action="store_true",
                    help="add the largest generated instances (LARGEST: flat planning takes >= 1 s)")
    ap.add_argument("--largest-only", action="store_true", help="only the largest generated instances")
    ap.add_argument("--time-limit", type=float, default=20.0, help="wall-clock limit per run (s)")
    ap.add_argument("--engine", choices=("auto", "forward", "regression"), default="forward",
                    help="the planner's engine at every level (default forward; 'auto' is the executive's "
                         "default: forward for concrete calls, regression for abstract ones)")
    ap.add_argument("--auto-strategy", default="hpn+refine-flat",
                    help="the strategy of the auto setting, before the settings `nowplan run --criticality auto` "
                         "adds (e.g. hpn+refine-flat+noregroup for the planner's order of abstract plans)")
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--tables-from", type=Path, nargs="+", default=[], metavar="CSV",
                    help="run nothing: write the tables of these CSVs (parts of one measurement, e.g. split "
                         "by domain to keep each command short) into --out")
    args = ap.parse_args(argv)
    domains = [d for d in args.domains.split(",") if d]
    args.larger = args.larger or args.larger_only
    args.largest = args.largest or args.largest_only
    args.out.mkdir(parents=True, exist_ok=True)
    rows: list[dict[str, Any]] = []
    t_start = time.perf_counter()
    for part in args.tables_from:
        with part.open() as fh:
            rows += list(csv.DictReader(fh))
    with tempfile.TemporaryDirectory() as tmp:
        todo = [] if args.tables_from else cases(domains, args.larger, Path(tmp), args.largest)
        for suite, d, inst, dom, prob, crit in todo:
            only = [t for t, flag in (("larger", args.larger_only), ("largest", args.largest_only)) if flag]
            if only and tier(inst) not in only:
                continue
            settings: list[tuple[str, str | None, str]] = [("flat", None, "flat"),
                                                           ("auto", "auto", args.auto_strategy)]
            if crit is not None:
                settings.append(("hand", str(crit), "hpn"))
            for name, c, strat in settings:
                row = {"suite": suite, "domain": d, "instance": inst, "setting": name,
                       **run_one(dom, prob, c, strat, args.time_limit, args.engine)}
                rows.append(row)
                print(f"{suite:9} {d:12} {inst:18} {name:5} {row['outcome']:8} cpu {row['planning_cpu_s']:8.3f} "
                      f"cost {row['cost']:6g} plans {row['plans_made']:4} fails {row['plan_failures']}",
                      flush=True)
    with (args.out / "criticality_auto.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                            text=True).stdout.strip()
    cmd = "benchmarks/criticality_auto.py " + " ".join(argv if argv is not None else sys.argv[1:])
    md = [f"# Automatic criticalities: HPN (`--criticality auto`) vs hand-written vs flat", "",
          f"`{cmd.strip()}` at {commit}, {datetime.date.today()}, "
          f"{time.perf_counter() - t_start:.0f} s in all (2-core shared VM; compare ratios within this run).",
          "Sums of planning CPU, wall and cost are over the instances that every setting of the domain solved.",
          "", summarize(rows), "", "## Whole runs per tier", "", whole_run_counts(rows), ""]
    if args.larger or any(tier(r["instance"]) == "larger" for r in rows):
        md += ["## Larger instances, one by one", "", larger_table(rows), ""]
    if args.largest or any(tier(r["instance"]) == "largest" for r in rows):
        md += ["## Largest instances, one by one", "", larger_table(rows, "largest-"), ""]
    (args.out / "criticality_auto.md").write_text("\n".join(md))
    print("\n".join(md))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
