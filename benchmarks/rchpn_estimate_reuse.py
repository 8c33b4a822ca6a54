"""Would caching RCHPN's resource estimates across steps pay (issue 19 target 3)?

Each step's ``Reorderer`` has a fresh ``Estimator`` (the belief changed).  For every estimate it
computes (a miss of its own per-step cache), this records whether an earlier step of the same run
computed the same key (action, level, order) and, if so, whether the value (uses, effort) was the
same, with the CPU s spent computing it (inclusive: a 1st-order estimate contains its small plan's
0th-order ones).

    PYTHONPATH=src .venv/bin/python benchmarks/rchpn_estimate_reuse.py --regime both --sizes 6,8,10 --trials 0-1
"""

from __future__ import annotations

import argparse
import time
from collections import Counter, defaultdict
from typing import Any

from nowplan.acting import resources as resources_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode

from bench_args import span  # benchmarks/bench_args.py, beside this script


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--regime", default="both")
    ap.add_argument("--sizes", default="6,8,10")
    ap.add_argument("--trials", default="0-1")
    args = ap.parse_args()
    counts: Counter[str] = Counter()
    cpu: dict[str, float] = defaultdict(float)
    seen: dict[Any, Any] = {}
    estimate = resources_mod.Estimator.estimate

    def recorded(self: Any, action: Any, levels: Any, order: int | None = None) -> Any:
        k = self.model.order(action) if order is None else order
        key = (action.key, levels.level(action), k)
        if key in self._cache:
            return self._cache[key]
        t0 = time.process_time()
        out = estimate(self, action, levels, order)
        dt = time.process_time() - t0
        value = (tuple(sorted((str(r), str(u)) for r, u in out.uses.items())), out.effort)
        kind = "first time" if key not in seen else "same as before" if seen[key] == value else "changed"
        counts[kind] += 1
        cpu[kind] += dt
        seen[key] = value
        return out

    resources_mod.Estimator.estimate = recorded  # type: ignore[method-assign]
    total = 0.0
    for trial in span(args.trials):
        for n in span(args.sizes):
            seen.clear()
            total += timed_run(episode(args.regime, n, trial), "hpn+peephole", trial, 600.0)[1]
    print(f"RCHPN CPU s: {total:.2f}; estimates computed: {sum(counts.values())}")
    print("| estimate | count | CPU s (inclusive) |\n|---|---|---|")
    for kind in ("first time", "same as before", "changed"):
        print(f"| {kind} | {counts[kind]} | {cpu[kind]:.3f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
