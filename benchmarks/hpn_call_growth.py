"""Where HPN's planning CPU per call grows with the packages on marsupial (issue 19 target 3).

Runs HPN on marsupial problems of two or more sizes and groups the executive's
planner calls by what they leave unmet (the one unmet goal atom's predicate and
argument types, or ``top`` for calls with several unmet atoms: the abstract plan
over every package); per group and size: calls per run share, mean CPU per call,
generated and expanded nodes, goal size.  The last line per group is its change in
CPU per call averaged over all calls (how much it adds to the growth of the mean).

    .venv/bin/python benchmarks/hpn_call_growth.py --regime single --sizes 5,20 --trials 0,1

Times are CPU seconds (``time.process_time``) outside any profiler; compare sizes
within one run (the machine is shared).
"""

from __future__ import annotations

import argparse
import time
from collections import Counter, defaultdict
from typing import Any

import nowplan.acting.hpn as hpn_mod
import nowplan.planning.regression as regression
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode


def group(domain: Any, objects: Any, belief: Any, goal: Any) -> str:
    unmet = [a for a in goal.atoms if not domain.holds(a, belief)]
    if len(unmet) != 1:
        return "top" if unmet else "none"
    a = unmet[0]
    return f"{a.predicate}(" + ",".join(str(objects.get(x, x)) for x in a.args) + ")"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--regime", default="single")
    ap.add_argument("--sizes", default="5,20")
    ap.add_argument("--trials", default="0,1")
    args = ap.parse_args()
    sizes = [int(x) for x in args.sizes.split(",")]
    trials = [int(x) for x in args.trials.split(",")]
    rows: list[dict[str, Any]] = []
    orig = regression.plan
    size = [0]

    def timed(domain: Any, objects: Any, belief: Any, goal: Any, *rest: Any, **kw: Any) -> Any:
        key = group(domain, objects, belief, goal)  # (outside the timed part)
        c0 = time.process_time()
        res = orig(domain, objects, belief, goal, *rest, **kw)
        rows.append({"n": size[0], "key": key, "cpu": time.process_time() - c0, "gen": res.generated,
                     "exp": res.expanded, "goal": len(goal)})
        return res

    hpn_mod.regression_plan = timed  # type: ignore[attr-defined]
    for n in sizes:
        size[0] = n
        for t in trials:
            timed_run(episode(args.regime, n, t), "hpn", t, 600.0)
    calls = Counter(r["n"] for r in rows)
    per_run = {n: sum(r["cpu"] for r in rows if r["n"] == n) / len(trials) for n in sizes}
    print(f"regime {args.regime}, trials {args.trials}")
    for n in sizes:
        print(f"  {n} packages: {calls[n] / len(trials):.0f} calls, plan CPU {per_run[n]:.3f} s per run, "
              f"{1000 * per_run[n] * len(trials) / calls[n]:.3f} ms per call")
    by: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for r in rows:
        by[r["key"]].append(r)
    lo, hi = sizes[0], sizes[-1]
    out = []
    for key, rs in by.items():
        lines = []
        share = {}
        for n in sizes:
            x = [r for r in rs if r["n"] == n]
            share[n] = 1000 * sum(r["cpu"] for r in x) / calls[n] if calls[n] else 0.0
            if x:
                k = len(x)
                ms = 1000 * sum(r["cpu"] for r in x) / k
                lines.append(f"    {n}: {k / calls[n]:.2f} of the calls, {ms:.2f} ms, "
                             f"generated {sum(r['gen'] for r in x) / k:.1f}, expanded {sum(r['exp'] for r in x) / k:.1f}, "
                             f"goal {sum(r['goal'] for r in x) / k:.1f} atoms")
        out.append((share[hi] - share[lo], key, lines))
    for d, key, lines in sorted(out, key=lambda x: -x[0]):
        print(f"  {key}: {d:+.3f} ms per call ({lo} -> {hi} packages)")
        print("\n".join(lines))


if __name__ == "__main__":
    main()
