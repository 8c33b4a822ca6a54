"""Where RCHPN's CPU goes beside HPN's on marsupial problems (seed 002, issue 19 target 3).

For each problem (``regime × packages × trial``) HPN and then RCHPN run in this one process, in
the order ``nowplan reproduce 002`` runs them, with exclusive timers (CPU s, ``time.process_time``)
around each part: a part's time excludes the parts called inside it, so the columns add up to
the whole run.

* ``exec``: the executive's planner calls (``Executive.make_plan``, ``direct_plan`` and the
  refinement check ``refine_without_swaps``), without the loader's searches inside them;
* ``applicable``: the peephole's highest true kernel (``Peephole.applicable``);
* ``next_step``: the rest of the peephole's rewrite (``Peephole.next_step``: SelectGap,
  SelectParallelOps, Gather, the trace record);
* ``estimate``: the estimator's bookkeeping (``Estimator.estimate``, ``effort``, ``effort_bound``)
  and ``small_plan``: its small regression searches, both without the loader;
* ``share``: the domain's shareability verdicts (``model._bay_shareable``) without the loader;
* ``valid``: the validity chains (``Reorderer.valid``);
* ``loader:<part>``: the loader's bay searches (``loader.AStar.run`` and the relaxed
  infeasibility test), by the part that asked for them;
* ``gc``: the collector's passes (``gc.callbacks``);
* ``other``: the rest (simulation, executive bookkeeping).

    PYTHONPATH=src .venv/bin/python benchmarks/rchpn_split.py --regimes both --sizes 8,10 --trials 0-3

Beside the exclusive parts, two inclusive tallies (CPU s with every part inside): ``windows``, the
peephole's rewrites (``Peephole._next_step``) by whether they changed the plan (``moved``: a
reorder or a combination; ``none``), and ``calls``, the executive's planner calls
(``Executive.make_plan``) by where they are made: for a combined step (``joint``), below one
(``below``), for a step taken alone after its combination was given up (``fallout``), or elsewhere
(``plain``; every HPN call).

``--profile FILE`` also writes a cProfile top list of each RCHPN run (``FILE.<problem>``).
``--out`` appends one JSON line per run (the split, CPU, cost and a digest of the executed actions,
to check that a change made the same decisions).
"""

from __future__ import annotations

import argparse
import cProfile
import functools
import gc
import hashlib
import io
import json
import pstats
import sys
import time
from collections import defaultdict
from pathlib import Path
from typing import Any

from nowplan.acting import hpn as hpn_mod
from nowplan.acting import peephole as peephole_mod
from nowplan.acting import reorder as reorder_mod
from nowplan.acting import resources as resources_mod
from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial import model as model_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode

from bench_args import span  # benchmarks/bench_args.py, beside this script

STRATEGIES = ("hpn", "hpn+peephole")


class Split:
    """Exclusive CPU timers: a stack of running parts, each charged its time minus its children's."""

    def __init__(self) -> None:
        self.totals: dict[str, float] = defaultdict(float)
        self.counts: dict[str, int] = defaultdict(int)
        self._stack: list[list[Any]] = []  # [part, start, time of children]
        self.tally: dict[str, tuple[int, float]] = {}

    def enter(self, part: str) -> None:
        if part == "loader" and self._stack:
            part = f"loader:{self._stack[-1][0].split(':')[-1]}"
        self._stack.append([part, time.process_time(), 0.0])

    def leave(self) -> None:
        part, start, children = self._stack.pop()
        dt = time.process_time() - start
        self.totals[part] += dt - children
        self.counts[part] += 1
        if self._stack:
            self._stack[-1][2] += dt

    def wrap(self, part: str, fn: Any) -> Any:
        @functools.wraps(fn)
        def timed(*args: Any, **kw: Any) -> Any:
            self.enter(part)
            try:
                return fn(*args, **kw)
            finally:
                self.leave()

        return timed

    def on_gc(self, phase: str, info: dict[str, Any]) -> None:
        if phase == "start":
            self.enter("gc")
        elif self._stack and self._stack[-1][0] == "gc":
            self.leave()

    def reset(self) -> None:
        self.totals.clear()
        self.counts.clear()
        self._stack.clear()
        self.tally.clear()

    def add(self, key: str, dt: float) -> None:
        """An inclusive tally (``windows:*``, ``calls:*``): count and CPU s."""
        n, t = self.tally.get(key, (0, 0.0))
        self.tally[key] = (n + 1, t + dt)


def install(split: Split) -> None:
    """Wrap each part where its callers look it up."""
    ex = hpn_mod.Executive
    ex.make_plan = split.wrap("exec", ex.make_plan)  # type: ignore[method-assign]
    ex.direct_plan = split.wrap("exec", ex.direct_plan)  # type: ignore[method-assign]
    hpn_mod.refine_without_swaps = split.wrap("exec", hpn_mod.refine_without_swaps)  # type: ignore[assignment]
    ph = peephole_mod.Peephole
    ph.applicable = split.wrap("applicable", ph.applicable)  # type: ignore[method-assign]
    ph.next_step = split.wrap("next_step", ph.next_step)  # type: ignore[method-assign]
    est = resources_mod.Estimator
    for name in ("estimate", "effort", "effort_bound"):
        setattr(est, name, split.wrap("estimate", getattr(est, name)))
    est.small_plan = split.wrap("small_plan", est.small_plan)  # type: ignore[method-assign]
    reorder_mod.Reorderer.valid = split.wrap("valid", reorder_mod.Reorderer.valid)  # type: ignore[method-assign]
    model_mod._bay_shareable = split.wrap("share", model_mod._bay_shareable)  # type: ignore[assignment]
    if hasattr(lp, "AStar"):
        lp.AStar.run = split.wrap("loader", lp.AStar.run)  # type: ignore[method-assign]
    else:  # a tree before the resumable search (for A/B runs against it)
        lp.search_status = split.wrap("loader", lp.search_status)
    model_mod.fetch_infeasible = split.wrap("loader", model_mod.fetch_infeasible)  # type: ignore[assignment]
    gc.callbacks.append(split.on_gc)
    rewrite = ph._next_step

    def windows(self: Any, ex: Any, frame: Any) -> Any:
        events, t0 = len(ex.trace.events), time.process_time()
        try:
            return rewrite(self, ex, frame)
        finally:  # a rewrite that changed the plan leaves its trace note
            split.add("windows:moved" if len(ex.trace.events) > events else "windows:none",
                      time.process_time() - t0)

    ph._next_step = windows  # type: ignore[method-assign]
    make_plan = ex.make_plan

    def calls(self: Any, goal: Any, levels: Any, parent: Any, *args: Any, **kw: Any) -> Any:
        t0 = time.process_time()
        try:
            return make_plan(self, goal, levels, parent, *args, **kw)
        finally:
            info = parent.info
            if info.get("joint") is not None and info.get("joint") == parent.i:
                kind = "joint"
            elif peephole_mod._combination(parent) is not None:
                kind = "below"
            elif info.get("fallout") is not None and info.get("fallout") == parent.i:
                kind = "fallout"
            else:
                kind = "plain"
            split.add(f"calls:{kind}", time.process_time() - t0)

    ex.make_plan = calls  # type: ignore[method-assign]


def one(regime: str, n: int, trial: int, strategy: str, split: Split, profile: str | None) -> dict[str, Any]:
    ep = episode(regime, n, trial)
    executed: list[str] = []
    world_execute = ep.world.execute

    def execute(action: Any) -> Any:
        executed.append(str(action))
        return world_execute(action)

    ep.world.execute = execute  # type: ignore[method-assign]
    split.reset()
    prof = cProfile.Profile() if profile and strategy != "hpn" else None
    if prof is not None:
        prof.enable()
    m, cpu, ok = timed_run(ep, strategy, trial, 600.0)
    if prof is not None:
        prof.disable()
        buf = io.StringIO()
        st = pstats.Stats(prof, stream=buf)
        st.sort_stats("cumulative").print_stats(45)
        st.sort_stats("tottime").print_stats(30)
        Path(f"{profile}.{regime}-{n}-t{trial}").write_text(buf.getvalue())
    parts = dict(split.totals)
    parts["other"] = cpu - sum(parts.values())
    return {"problem": f"{regime}-{n}", "trial": trial, "strategy": strategy, "cpu": cpu, "ok": ok,
            "cost": m.execution_cost, "actions": hashlib.sha1("\n".join(executed).encode()).hexdigest()[:12],
            "parts": {k: round(v, 4) for k, v in sorted(parts.items())},
            "counts": dict(sorted(split.counts.items())),
            "tally": {k: [n, round(t, 4)] for k, (n, t) in sorted(split.tally.items())}}


def table(rows: list[dict[str, Any]]) -> str:
    by: dict[str, dict[str, float]] = {s: defaultdict(float) for s in STRATEGIES}
    cpu = {s: 0.0 for s in STRATEGIES}
    for r in rows:
        cpu[r["strategy"]] += r["cpu"]
        for k, v in r["parts"].items():
            by[r["strategy"]][k] += v
    keys = sorted(set(by["hpn"]) | set(by["hpn+peephole"]))
    lines = ["| part | HPN s | RCHPN s | RCHPN − HPN s | share of the extra |", "|---|---|---|---|---|"]
    extra = cpu["hpn+peephole"] - cpu["hpn"]
    for k in sorted(keys, key=lambda k: -(by["hpn+peephole"][k] - by["hpn"][k])):
        d = by["hpn+peephole"][k] - by["hpn"][k]
        lines.append(f"| {k} | {by['hpn'][k]:.3f} | {by['hpn+peephole'][k]:.3f} | {d:+.3f} | "
                     f"{100 * d / extra if extra else 0:.0f} % |")
    lines.append(f"| whole run | {cpu['hpn']:.3f} | {cpu['hpn+peephole']:.3f} | {extra:+.3f} | "
                 f"RCHPN/HPN {cpu['hpn+peephole'] / cpu['hpn']:.2f} |")
    tally: dict[str, dict[str, list[float]]] = {s: defaultdict(lambda: [0.0, 0.0]) for s in STRATEGIES}
    for r in rows:
        for k, (n, t) in r.get("tally", {}).items():
            tally[r["strategy"]][k][0] += n
            tally[r["strategy"]][k][1] += t
    if any(tally.values()):
        lines += ["", "| inclusive tally | HPN n | HPN s | RCHPN n | RCHPN s | RCHPN − HPN s | share of the extra |",
                  "|---|---|---|---|---|---|---|"]
        for k in sorted(set(tally["hpn"]) | set(tally["hpn+peephole"])):
            h, p = tally["hpn"].get(k, [0, 0.0]), tally["hpn+peephole"].get(k, [0, 0.0])
            d = p[1] - h[1]
            lines.append(f"| {k} | {h[0]:.0f} | {h[1]:.3f} | {p[0]:.0f} | {p[1]:.3f} | {d:+.3f} | "
                         f"{100 * d / extra if extra else 0:.0f} % |")
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--regimes", default="both")
    ap.add_argument("--sizes", default="8")
    ap.add_argument("--trials", default="0")
    ap.add_argument("--profile", help="write a cProfile top list of each RCHPN run to FILE.<problem>")
    ap.add_argument("--out", type=Path, help="append one JSON line per run")
    ap.add_argument("--summarize", type=Path, nargs="+", help="print the table from stored lines and stop")
    args = ap.parse_args()
    if args.summarize:
        rows = [json.loads(x) for p in args.summarize for x in p.read_text().splitlines() if x.strip()]
        print(table(rows))
        return 0
    split = Split()
    install(split)
    rows = []
    for trial in span(args.trials):
        for n in span(args.sizes):
            for regime in args.regimes.split(","):
                for strategy in STRATEGIES:
                    r = one(regime, n, trial, strategy, split, args.profile)
                    rows.append(r)
                    print(f"{r['problem']} t{trial} {strategy}: {r['cpu']:.2f} s, cost {r['cost']:g}, "
                          f"actions {r['actions']}", file=sys.stderr)
                    if args.out:
                        with args.out.open("a") as fh:
                            fh.write(json.dumps(r) + "\n")
    print(table(rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
