"""HPN's planner calls on marsupial per leg of the packages' routes (issue 19 target 3).

A package's route has one leg per vehicle that carries it (truck, plane, truck: three legs;
a package whose destination is in its own city: one).  HPN refines each leg with the same
planner calls (its unload, its load, the vehicle's two travels, the unload again with the
vehicle there and once more with the loader's placement), so the calls per run follow the
legs, and the legs per package depend on where each instance puts its packages.  Per
problem (``regime × packages × trial``) this prints the legs (``unload`` steps of the
top-level plan), the planner calls, calls per leg and the planner's CPU per call and per
leg, then fitted exponents of plan CPU, calls and CPU per call against the packages and
against the legs (least squares on log-log over the sizes' means).

    .venv/bin/python benchmarks/hpn_legs.py --regime single --sizes 3,5,8,12,16,20 --trials 0,1,2,3 \\
        --out benchmarks/results/hpn_growth_HASH/legs_single.jsonl

Times are CPU seconds (``time.process_time``) inside ``regression.plan``; compare within one run.
``--profile`` runs the planner calls (only them) under cProfile and prints the function calls per
planner call for each size: a count that the machine's load does not change (timings then mean nothing).
"""

from __future__ import annotations

import argparse
import cProfile
import json
import math
import pstats
import time
from pathlib import Path
from typing import Any

import nowplan.acting.hpn as hpn_mod
import nowplan.planning.regression as regression
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode


def slope(xs: list[float], ys: list[float]) -> float:
    """Least-squares slope of log y against log x."""
    lx, ly = [math.log(x) for x in xs], [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    den = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly, strict=True)) / den if den else float("nan")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--regime", default="single")
    ap.add_argument("--sizes", default="3,5,8,12,16,20")
    ap.add_argument("--trials", default="0,1,2,3")
    ap.add_argument("--out", type=Path, default=None, help="append one JSON line per problem")
    ap.add_argument("--profile", action="store_true", help="count function calls per planner call (cProfile)")
    args = ap.parse_args()
    sizes = [int(x) for x in args.sizes.split(",")]
    trials = [int(x) for x in args.trials.split(",")]
    state: dict[str, Any] = {}
    make_plan = hpn_mod.Executive.make_plan
    orig = regression.plan

    def root_legs(self: Any, goal: Any, levels: Any, parent: Any, *rest: Any, **kw: Any) -> Any:
        plan = make_plan(self, goal, levels, parent, *rest, **kw)
        if parent.root and plan is not None and "legs" not in state:
            state["legs"] = sum(1 for s in plan.steps if s.action is not None and s.action.name == "unload")
        return plan

    prof: list[cProfile.Profile] = []

    def timed(*a: Any, **kw: Any) -> Any:
        c0 = time.process_time()
        if prof:
            prof[0].enable()
        try:
            return orig(*a, **kw)
        finally:
            if prof:
                prof[0].disable()
            state["cpu"] += time.process_time() - c0
            state["calls"] += 1

    hpn_mod.Executive.make_plan = root_legs  # type: ignore[method-assign]
    hpn_mod.regression_plan = timed  # type: ignore[attr-defined]
    rows: list[dict[str, Any]] = []
    print("| packages | trial | legs | calls | calls per leg | plan CPU s | ms per call | ms per leg |")
    print("|---|---|---|---|---|---|---|---|")
    counts: dict[int, float] = {}
    for n in sizes:
        if args.profile:
            prof[:] = [cProfile.Profile()]
        for t in trials:
            state.clear()
            state.update(cpu=0.0, calls=0)
            timed_run(episode(args.regime, n, t), "hpn", t, 600.0)
            r = {"regime": args.regime, "packages": n, "trial": t, "legs": state.get("legs", 0),
                 "calls": state["calls"], "plan_cpu": round(state["cpu"], 6)}
            rows.append(r)
            legs = max(r["legs"], 1)
            print(f"| {n} | {t} | {r['legs']} | {r['calls']} | {r['calls'] / legs:.2f} | {r['plan_cpu']:.3f} | "
                  f"{1000 * r['plan_cpu'] / r['calls']:.2f} | {1000 * r['plan_cpu'] / legs:.2f} |", flush=True)
            if args.out is not None:
                with args.out.open("a") as fh:
                    fh.write(json.dumps(r) + "\n")
        if prof:
            st = pstats.Stats(prof[0]).stats  # type: ignore[attr-defined]
            calls_n = sum(r["calls"] for r in rows if r["packages"] == n)
            counts[n] = sum(v[1] for v in st.values()) / max(calls_n, 1)
    mean = {n: {k: sum(r[k] for r in rows if r["packages"] == n) / len(trials) for k in ("legs", "calls", "plan_cpu")}
            for n in sizes}
    ns = [float(n) for n in sizes]
    legs = [mean[n]["legs"] for n in sizes]
    cpu = [mean[n]["plan_cpu"] for n in sizes]
    calls = [mean[n]["calls"] for n in sizes]
    per_call = [c / k for c, k in zip(cpu, calls, strict=True)]
    if counts:
        print("function calls per planner call (cProfile): " + ", ".join(f"{n}: {c:.0f}" for n, c in counts.items()))
    per_pkg = ", ".join(f"{n}: {mean[n]['legs'] / n:.2f}" for n in sizes)
    print(f"\nlegs per package: {per_pkg}")
    if len(sizes) > 1:
        print(f"against packages: plan CPU n^{slope(ns, cpu):.2f}, calls n^{slope(ns, calls):.2f}, "
              f"per call n^{slope(ns, per_call):.2f}, legs n^{slope(ns, legs):.2f}")
        print(f"against legs:     plan CPU L^{slope(legs, cpu):.2f}, calls L^{slope(legs, calls):.2f}, "
              f"per call L^{slope(legs, per_call):.2f}")


if __name__ == "__main__":
    main()
