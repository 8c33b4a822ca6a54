"""Audit of the ``h2`` switch in the executive: every planner call of ``hpn+h2`` runs again without h2.

For each call with ``PlannerConfig.h2`` the same call (same belief, goal, levels, context, and a copy
of the random generator's state) is repeated with ``h2=False``, and the two statuses are counted.
Where the call without h2 found a plan and the call with it did not, the plan found is checked step
by step: a pre-image holding a pair the h² table proves no reachable state holds together is a plan
no refinement can carry out (pruning it is right); a call lost without such a pair would be a search
that h2 made unlucky, and an UNSOLVABLE answer against a plan would be unsound pruning.

    PYTHONPATH=src:examples/gridfix:examples/mine .venv/bin/python benchmarks/h2_audit.py --seeds 0-5
"""

from __future__ import annotations

import argparse
import dataclasses
import random
from collections import Counter
from typing import Any

import nowplan.acting.hpn as hpn
import nowplan.planning.regression as reg
from nowplan.planning.regression_search import _Search


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", default="0-5", help="a range a-b")
    ap.add_argument("--strategy", default="hpn+h2")
    args = ap.parse_args(argv)
    lo, hi = (int(x) for x in args.seeds.split("-"))
    orig = reg.plan
    stats: Counter[str] = Counter()
    calls = [0]

    def audited(domain: Any, objects: Any, belief: Any, goal: Any, levels: Any = None, config: Any = None,
                context: Any = None, rng: random.Random | None = None) -> Any:
        state = rng.getstate() if rng is not None else None
        r = orig(domain, objects, belief, goal, levels, config, context, rng)
        if config is None or not config.h2:
            return r
        again = None
        if state is not None:
            again = random.Random()
            again.setstate(state)
        r0 = orig(domain, objects, belief, goal, levels, dataclasses.replace(config, h2=False), context, again)
        stats[f"with h2 {r.status.name.lower()}, without {r0.status.name.lower()}"] += 1
        calls[0] += 1
        if r0.solved and not r.solved:
            pr = _Search(domain, objects, belief, levels, config, context).pairs()
            T = domain.facts
            hit = None
            for step in r0.plan.steps if pr is not None else ():
                ids = [T.id(a) for a in step.goal.atoms]
                if pr.excluded(ids):
                    hit = step
                    break
            if r.status.name == "UNSOLVABLE":
                stats["UNSOUND: unsolvable with h2, a plan without"] += 1
            elif hit is not None:
                stats["lost plans through a pair h2 excludes (not refinable)"] += 1
            else:
                stats["lost plans without an excluded pair (search order)"] += 1
        return r

    reg.plan = audited  # type: ignore[assignment]
    hpn.regression_plan = audited  # type: ignore[assignment]
    from nowplan.api import parse_strategy, run_episode
    from gridfix_domain.scenarios import episode as gridfix
    from mine_domain.scenarios import episode as mine

    cases = [("gridfix clean", gridfix, {}), ("gridfix f0.2-m0.1-p0.05", gridfix,
                                              {"failure_prob": 0.2, "miss": 0.1, "fp": 0.05}),
             ("mine clean", mine, {})]
    for name, ep, kw in cases:
        before = calls[0]
        for seed in range(lo, hi + 1):
            run_episode(ep(seed, **kw), parse_strategy(args.strategy), seed=seed)
        print(f"{name}, seeds {lo}-{hi}: {calls[0] - before} calls audited")
    for k, v in sorted(stats.items()):
        print(f"{v:6d}  {k}")
    return 1 if stats["UNSOUND: unsolvable with h2, a plan without"] else 0


if __name__ == "__main__":
    raise SystemExit(main())
