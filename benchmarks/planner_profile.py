"""The regression planner's speed on the problems HPN and RCHPN solve (issue 19).

For each marsupial problem (``regime × packages × trial``) and strategy (``hpn``,
``hpn+peephole``) and for logistics HPN on the generated problems of
``benchmarks/flat_logistics.py``, one line per run with

* ``calls``: regression-planner calls (the executive's plans, RCHPN's joint plans
  and the peephole estimator's small plans), ``joint`` of them with the
  serialization shortcut switched off by the peephole (combined subgoals);
* ``nodes``: nodes expanded over all calls; ``plan_cpu``: CPU s inside the planner
  (all calls); ``nodes/s``; ``joint_cpu``: CPU s of the joint calls;
* ``cost``: execution cost; ``cpu``: CPU s of the whole run; ``actions``: a digest
  of the executed action sequence (to check that a change made the same decisions).

    .venv/bin/python benchmarks/planner_profile.py --regimes single,both --sizes 3,5,8 \\
        --trials 0,1 --logistics 20 --out benchmarks/results/planner_profile_before.jsonl
    .venv/bin/python benchmarks/planner_profile.py --regimes single --sizes 8 --trials 0 \\
        --strategies hpn --no-logistics --profile prof.txt

``--flat-logistics 10,14,20`` adds one flat ``--engine regression`` call per generated logistics
problem and seed (a search of hundreds of nodes per call: the per-node figure of the search itself);
``--loop python`` runs the regression search's Python loop instead of its compiled one
(:mod:`nowplan.planning.regression_native`) for an A/B in one session:

    .venv/bin/python benchmarks/planner_profile.py --regimes single,both --sizes 3,5,8 --trials 0,1 \
        --strategies hpn --logistics 20 --flat-logistics 10,14,20 --loop python --tag python --out AB.jsonl

``--profile FILE`` runs everything under cProfile and writes the top 20 functions
by cumulative and by internal time.  Times are CPU seconds (``time.process_time``);
the machine is shared, so compare ratios within one run.
"""

from __future__ import annotations

import argparse
import cProfile
import hashlib
import io
import json
import pstats
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import nowplan.acting.hpn as hpn_mod
import nowplan.acting.resources as resources_mod
import nowplan.planning.regression as regression
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.levels import flat_levels
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
from nowplan.domains.registry import Episode
from nowplan.experiments import progress
from nowplan.io.logistics_gen import generate_logistics
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.regression import PlannerConfig
from nowplan.planning.regression_search import _Search
from nowplan.worlds.symbolic import SymbolicWorld

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "logistics"
# (cities, locations per city, airplanes, packages), as in flat_logistics.py
LOGISTICS = {2: (2, 2, 1, 2), 4: (2, 3, 1, 4), 6: (3, 3, 1, 6), 8: (4, 3, 2, 8), 10: (5, 3, 2, 10),
             14: (6, 4, 2, 14), 20: (8, 4, 3, 20)}


class Counter:
    """Wraps the regression planner wherever the executive and the estimator call it."""

    def __init__(self) -> None:
        self.reset()
        self._orig = regression.plan

    def reset(self) -> None:
        self.calls = self.joint = self.nodes = 0
        self.cpu = self.joint_cpu = 0.0

    def wrap(self, source: str) -> Any:
        orig = regression.plan

        def counted(*args: Any, **kw: Any) -> Any:
            c0 = time.process_time()
            res = orig(*args, **kw)
            dt = time.process_time() - c0
            cfg = args[5] if len(args) > 5 else kw.get("config")
            self.calls += 1
            self.nodes += res.expanded
            self.cpu += dt
            if source == "exec" and cfg is not None and not cfg.serialization:
                self.joint += 1
                self.joint_cpu += dt
            return res

        return counted

    def install(self) -> None:
        hpn_mod.regression_plan = self.wrap("exec")  # type: ignore[assignment]
        resources_mod.plan = self.wrap("estimator")  # type: ignore[assignment]


def digest(actions: list[str]) -> str:
    return hashlib.sha1("\n".join(actions).encode()).hexdigest()[:12]


def record(ep: Episode) -> list[str]:
    executed: list[str] = []
    world = ep.world
    original = world.execute

    def execute(action: Any) -> Any:
        executed.append(str(action))
        return original(action)

    world.execute = execute  # type: ignore[method-assign]
    return executed


def marsupial_run(regime: str, n: int, trial: int, strategy: str, limit: float, ctr: Counter) -> dict[str, Any]:
    ep = episode(regime, n, trial)
    executed = record(ep)
    ctr.reset()
    m, cpu, ok = timed_run(ep, strategy, trial, limit)
    return row("marsupial", f"{regime}-{n}", trial, strategy, m, cpu, ok, executed, ctr)


LOGISTICS_PLANNER: dict[str, Any] = {}


def logistics_run(n: int, seed: int, limit: float, ctr: Counter) -> dict[str, Any]:
    c, loc, a, _ = LOGISTICS[n]
    with tempfile.TemporaryDirectory() as tmp:
        prob = Path(tmp) / f"p-c{c}-l{loc}-a{a}-n{n}-s{seed}.pddl"
        prob.write_text(generate_logistics(c, loc, a, n, seed=seed))
        p = load_pddl(DATA / "domain.pddl", prob, DATA / "logistics.crit")
    ep = Episode(p, SymbolicWorld(p.domain, p.init), SymbolicBelief(p.init))
    executed = record(ep)
    ctr.reset()
    cfg = PlannerConfig(time_limit=limit, **LOGISTICS_PLANNER)
    st = parse_strategy("hpn", time_limit=limit, max_actions=10_000, planner=cfg)
    c0 = time.process_time()
    m = run_episode(ep, st)
    cpu = time.process_time() - c0
    ok = bool(p.domain.satisfies(ep.world.state, p.goal))
    return row("logistics", f"log-{n}", seed, "hpn", m, cpu, ok, executed, ctr)


def flat_logistics_run(n: int, seed: int, limit: float) -> dict[str, Any]:
    """One flat regression call on a generated logistics problem (the search's own nodes per second)."""
    c, loc, a, _ = LOGISTICS[n]
    with tempfile.TemporaryDirectory() as tmp:
        prob = Path(tmp) / f"p-c{c}-l{loc}-a{a}-n{n}-s{seed}.pddl"
        prob.write_text(generate_logistics(c, loc, a, n, seed=seed))
        p = load_pddl(DATA / "domain.pddl", prob)
    cfg = PlannerConfig(time_limit=limit, clock="cpu", engine="regression", serialization=False,
                        monotonic=False, max_nodes=200_000, weight=2.0)  # as nowplan plan --engine regression
    inner = [0.0]  # CPU s inside the search itself (_Search.run: the loop, without grounding and h_add set-up)
    run = _Search.run

    def timed(self: _Search, *a: Any, **k: Any) -> Any:
        t = time.process_time()
        try:
            return run(self, *a, **k)
        finally:
            inner[0] += time.process_time() - t

    _Search.run = timed  # type: ignore[method-assign]
    try:
        c0 = time.process_time()
        res = regression.plan(p.domain, p.objects, SymbolicBelief(p.init), p.goal, flat_levels(), cfg)
        cpu = time.process_time() - c0
    finally:
        _Search.run = run  # type: ignore[method-assign]
    steps = [] if res.plan is None else [str(s.action) for s in res.plan.steps[1:]]
    return {"domain": "logistics-flat", "problem": f"log-{n}", "trial": seed, "strategy": "regression",
            "outcome": res.status.value, "goal_holds": res.solved, "cost": None if res.plan is None else len(steps),
            "n_actions": len(steps), "calls": 1, "joint": 0, "nodes": res.expanded, "generated": res.generated,
            "plan_cpu": round(cpu, 4), "joint_cpu": 0.0,
            "nodes_per_s": round(res.expanded / cpu) if cpu else None, "search_cpu": round(inner[0], 4),
            "search_nodes_per_s": round(res.expanded / inner[0]) if inner[0] else None,
            "cpu": round(cpu, 4), "actions": digest(steps)}


def row(domain: str, problem: str, trial: int, strategy: str, m: Any, cpu: float, ok: bool,
        executed: list[str], ctr: Counter) -> dict[str, Any]:
    return {
        "domain": domain, "problem": problem, "trial": trial, "strategy": strategy,
        "outcome": m.outcome.value, "goal_holds": ok, "cost": m.execution_cost, "n_actions": len(executed),
        "calls": ctr.calls, "joint": ctr.joint, "nodes": ctr.nodes, "plan_cpu": round(ctr.cpu, 4),
        "joint_cpu": round(ctr.joint_cpu, 4), "nodes_per_s": round(ctr.nodes / ctr.cpu) if ctr.cpu else None,
        "cpu": round(cpu, 4), "actions": digest(executed),
    }


def overrides(spec: str) -> dict[str, Any]:
    """``"heuristic=hff,weight=2"`` as PlannerConfig keyword arguments (typed like the defaults)."""
    kw: dict[str, Any] = {}
    for item in filter(None, spec.split(",")):
        k, v = item.split("=")
        default = getattr(PlannerConfig(), k)
        kind = str if default is None else type(default)
        kw[k] = (v.lower() in ("1", "true", "yes")) if kind is bool else kind(v)
    return kw


def summarize(paths: list[Path]) -> None:
    """Per regime and size: mean planning CPU and nodes/s of HPN and RCHPN, the CPU ratio and cost decrease."""
    import statistics as st
    from collections import defaultdict

    runs: dict[tuple[str, int, str], dict[str, Any]] = {}
    for path in paths:
        for line in path.read_text().splitlines():
            r = json.loads(line)
            runs[(r["problem"], r["trial"], r["strategy"])] = r
    table: dict[tuple[str, str], list[tuple[dict[str, Any], dict[str, Any] | None]]] = defaultdict(list)
    for (problem, trial, strategy), r in runs.items():
        if strategy == "hpn":
            regime, _, size = problem.rpartition("-")
            q = runs.get((problem, trial, "hpn+peephole"))
            table[(regime, size)].append((r, q))
            table[(regime, "all")].append((r, q))
    print("| regime | packages | problems | HPN CPU s | HPN plan CPU s | HPN nodes/s | RCHPN CPU s | "
          "RCHPN nodes/s | RCHPN/HPN CPU (ratio of means) | cost decrease % | unsolved R/H |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for (regime, size), pairs in sorted(table.items(), key=lambda kv: (kv[0][0], kv[0][1] == "all",
                                                                       kv[0][1].zfill(3))):
        h = [r for r, _ in pairs]
        q = [x for _, x in pairs if x is not None]
        row = f"| {regime} | {size} | {len(pairs)} | {st.mean(r['cpu'] for r in h):.3f} | " \
              f"{st.mean(r['plan_cpu'] for r in h):.3f} | " \
              f"{sum(r['nodes'] for r in h) / max(sum(r['plan_cpu'] for r in h), 1e-9):.0f} |"
        if q:
            ok = [(r, x) for r, x in pairs if x is not None and r["goal_holds"] and x["goal_holds"]]
            dec = [100 * (1 - x["cost"] / r["cost"]) for r, x in ok]
            row += f" {st.mean(x['cpu'] for x in q):.3f} | " \
                   f"{sum(x['nodes'] for x in q) / max(sum(x['plan_cpu'] for x in q), 1e-9):.0f} | " \
                   f"{st.mean(x['cpu'] for x in q) / st.mean(r['cpu'] for r, x in pairs if x is not None):.2f} | " \
                   f"{st.mean(dec) if dec else float('nan'):.1f} | " \
                   f"{sum(not x['goal_holds'] for x in q)}/{sum(not r['goal_holds'] for r in h)} |"
        else:
            row += " | | | | |"
        print(row)


def fit(paths: list[Path]) -> None:
    """Per tag and regime: mean plan CPU, calls and CPU per call by size, and their fitted growth n^k.

    ``k`` is the least-squares slope of log(mean) against log(packages) over the sizes
    (HPN rows only); rows of one tag and problem that repeat keep the last.
    """
    import math
    import statistics as st
    from collections import defaultdict

    runs: dict[tuple[str, str, int], dict[str, Any]] = {}
    for path in paths:
        for line in path.read_text().splitlines():
            r = json.loads(line)
            if r["domain"] == "marsupial" and r["strategy"] == "hpn":
                runs[(r.get("tag", ""), r["problem"], r["trial"])] = r
    by: dict[tuple[str, str], dict[int, list[dict[str, Any]]]] = defaultdict(lambda: defaultdict(list))
    for (tag, problem, _), r in runs.items():
        regime, _, size = problem.rpartition("-")
        by[(tag, regime)][int(size)].append(r)

    def slope(xs: list[float], ys: list[float]) -> float:
        lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
        mx, my = st.mean(lx), st.mean(ly)
        return sum((a - mx) * (b - my) for a, b in zip(lx, ly, strict=True)) / sum((a - mx) ** 2 for a in lx)

    print("| tag | regime | packages: plan CPU s (calls, ms per call) | plan CPU n^k | calls n^k | per call n^k |")
    print("|---|---|---|---|---|---|")
    for (tag, regime), sizes in sorted(by.items()):
        ns = sorted(sizes)
        cpu = [st.mean(r["plan_cpu"] for r in sizes[n]) for n in ns]
        calls = [st.mean(r["calls"] for r in sizes[n]) for n in ns]
        per = [1000 * c / k for c, k in zip(cpu, calls, strict=True)]
        cells = ", ".join(f"{n}: {c:.3f} ({k:.0f}, {q:.2f})" for n, c, k, q in zip(ns, cpu, calls, per, strict=True))
        fits = [f"{slope(ns, ys):.2f}" if len(ns) > 1 else "" for ys in (cpu, calls, per)]
        print(f"| {tag} | {regime} | {cells} | {' | '.join(fits)} |")


def loop_table(paths: list[Path]) -> None:
    """Rows tagged ``python-R`` / ``compiled-R`` (rounds R): per group, each loop's median over the
    rounds of the summed planning CPU and nodes/s, the search's own nodes/s (flat rows), the
    ratio, and whether both loops expanded the same nodes and executed the same actions."""
    import statistics as st
    from collections import defaultdict

    sums: dict[tuple[str, str], dict[str, dict[str, list[float]]]] = defaultdict(lambda: defaultdict(
        lambda: defaultdict(list)))
    same: dict[tuple[str, str], set[tuple[str, tuple[Any, ...]]]] = defaultdict(set)
    per: dict[tuple[str, str, str, str], list[float]] = defaultdict(lambda: [0.0, 0.0, 0.0, 0.0])
    for path in paths:
        for line in path.read_text().splitlines():
            r = json.loads(line)
            loop, _, rnd = r["tag"].partition("-")
            group = (r["domain"], r["problem"].rsplit("-", 1)[0] if r["domain"] == "marsupial" else r["problem"])
            acc = per[(*group, loop, rnd)]
            acc[0] += r["plan_cpu"]
            acc[1] += r["nodes"]
            acc[2] += r.get("search_cpu", 0.0)
            acc[3] += r["calls"]
            same[group].add((loop, (r["problem"], r["trial"], r["nodes"], r["actions"])))
    for (dom, prob, loop, _), (cpu, nodes, scpu, calls) in per.items():
        cell = sums[(dom, prob)][loop]
        cell["cpu"].append(cpu)
        cell["nps"].append(nodes / cpu if cpu else 0.0)
        cell["snps"].append(nodes / scpu if scpu else 0.0)
        cell["nodes"].append(nodes)
        cell["calls"].append(calls)
    print("| group | calls | nodes | Python loop: planning CPU s, nodes/s (search alone) | compiled: planning CPU s, "
          "nodes/s (search alone) | CPU ratio | same nodes and actions |")
    print("|---|---|---|---|---|---|---|")
    for group, loops in sums.items():
        py, c = loops["python"], loops["compiled"]

        def cell(x: dict[str, list[float]]) -> str:
            out = f"{st.median(x['cpu']):.3f}, {st.median(x['nps']):,.0f}"
            return out + (f" ({st.median(x['snps']):,.0f})" if st.median(x["snps"]) else "")

        rows = {loop: {k for lp, k in same[group] if lp == loop} for loop in ("python", "compiled")}
        print(f"| {' '.join(group)} | {st.median(c['calls']):.0f} | {st.median(c['nodes']):,.0f} | {cell(py)} | "
              f"{cell(c)} | {st.median(py['cpu']) / st.median(c['cpu']):.1f}x | "
              f"{'yes' if rows['python'] == rows['compiled'] else 'NO'} |")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--regimes", default="single,both")
    ap.add_argument("--sizes", default="3,5,8")
    ap.add_argument("--trials", default="0,1")
    ap.add_argument("--strategies", default="hpn,hpn+peephole")
    ap.add_argument("--logistics", default="20", help="logistics package counts (flat_logistics sizes)")
    ap.add_argument("--no-logistics", action="store_true")
    ap.add_argument("--flat-logistics", default="", help="logistics package counts for one flat regression call each")
    ap.add_argument("--loop", choices=("compiled", "python"), default="compiled",
                    help="the regression search's loop: compiled where it runs (default) or Python")
    ap.add_argument("--no-marsupial", action="store_true")
    ap.add_argument("--logistics-seeds", default="0,1")
    ap.add_argument("--limit-s", type=float, default=600.0, help="CPU s per run")
    ap.add_argument("--profile", type=Path, help="write a cProfile top 20 here")
    ap.add_argument("--out", type=Path, help="append the rows (JSON lines) here")
    ap.add_argument("--planner", default="", help="marsupial PlannerConfig overrides, e.g. heuristic=hff,weight=1")
    ap.add_argument("--logistics-planner", default="", help="logistics PlannerConfig overrides")
    ap.add_argument("--tag", default="", help="a label stored in each row")
    ap.add_argument("--loop-table", type=Path, nargs="+",
                    help="print the Python/compiled loop A/B table of rows tagged python-R / compiled-R and stop")
    ap.add_argument("--summarize", type=Path, nargs="+", help="print tables from stored rows and stop")
    ap.add_argument("--fit", action="store_true",
                    help="with --summarize: HPN's growth per tag and regime (fitted exponents of plan CPU, "
                         "calls and CPU per call against the number of packages)")
    args = ap.parse_args()
    if args.loop_table:
        loop_table(args.loop_table)
        return 0
    if args.summarize:
        (fit if args.fit else summarize)(args.summarize)
        return 0
    if args.planner:
        import dataclasses

        import nowplan.domains.marsupial.model as model

        model.PLANNER = dataclasses.replace(model.PLANNER, **overrides(args.planner))
    LOGISTICS_PLANNER.update(overrides(args.logistics_planner))
    _Search.native = args.loop == "compiled"
    ctr = Counter()
    ctr.install()
    jobs: list[Any] = []
    if not args.no_marsupial:
        for regime in args.regimes.split(","):
            for n in map(int, args.sizes.split(",")):
                for trial in map(int, args.trials.split(",")):
                    for st in args.strategies.split(","):
                        jobs.append(lambda r=regime, n=n, t=trial, s=st: marsupial_run(r, n, t, s, args.limit_s, ctr))
    if not args.no_logistics:
        for n in map(int, args.logistics.split(",")):
            for seed in map(int, args.logistics_seeds.split(",")):
                jobs.append(lambda n=n, s=seed: logistics_run(n, s, args.limit_s, ctr))
    for n in map(int, filter(None, args.flat_logistics.split(","))):
        for seed in map(int, args.logistics_seeds.split(",")):
            jobs.append(lambda n=n, s=seed: flat_logistics_run(n, s, args.limit_s))
    prof = cProfile.Profile() if args.profile else None
    rows = []
    bar = progress.bar(len(jobs), "planner_profile")
    for job in jobs:
        if prof is not None:
            prof.enable()
        r = job()
        if prof is not None:
            prof.disable()
        if args.tag:
            r["tag"] = args.tag
        rows.append(r)
        progress.echo(json.dumps(r))
        bar.update(1)
        if args.out:
            with args.out.open("a") as fh:
                fh.write(json.dumps(r) + "\n")
    bar.close()
    if prof is not None:
        buf = io.StringIO()
        st = pstats.Stats(prof, stream=buf)
        st.sort_stats("cumulative").print_stats(20)
        st.sort_stats("tottime").print_stats(20)
        args.profile.write_text(buf.getvalue())
    return 0


if __name__ == "__main__":
    sys.exit(main())
