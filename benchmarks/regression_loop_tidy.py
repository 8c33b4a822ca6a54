"""The held-out tidy house's top-level planner call on the Python and the compiled regression loop.

The house (examples/tidy) has plain conflict rules and a place cost that is a plain callable
(so it is costed per call); the call is HPN's first, the whole goal at the top level, by the
regression engine.  Rows: the example as it is, and with its callable costs declared
``StateFreeCost``; each loop twice, alternating, CPU seconds of the call::

    PYTHONPATH=src:examples/tidy .venv/bin/python benchmarks/regression_loop_tidy.py [--seed 0] [--rounds 2]
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from typing import Any

from nowplan.core.levels import LevelMap
from nowplan.core.operators import StateFreeCost
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search

from tidy_domain.scenarios import problem


class Declared(StateFreeCost):
    """The example's callable cost, declared not to read the belief (it does not)."""

    def __init__(self, fn: Any) -> None:
        self.fn = fn

    def __call__(self, bindings: Any, belief: Any = None) -> float:
        return float(self.fn(bindings, None))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--rounds", type=int, default=2)
    args = ap.parse_args()
    p, belief = problem(args.seed, "tidy")
    declared = replace(p.domain, operators=tuple(replace(o, cost=Declared(o.cost)) if callable(o.cost) else o
                                                 for o in p.domain.operators))
    print("| costs | loop | status | expanded | steps | CPU s |")
    print("|---|---|---|---|---|---|")
    for name, dom in (("as in the example (callable)", p.domain), ("declared StateFreeCost", declared)):
        for _ in range(args.rounds):
            for native in (False, True):
                _Search.native = native
                c0 = time.process_time()
                r = plan(dom, p.objects, belief, p.goal, LevelMap(dom.top_level),
                         PlannerConfig(engine="regression", time_limit=60, clock="cpu"))
                cpu = time.process_time() - c0
                steps = len(r.plan) if r.plan is not None else None
                print(f"| {name} | {'compiled' if native else 'python'} | {r.status.value} | {r.expanded} | "
                      f"{steps} | {cpu:.3f} |")
    _Search.native = True
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
