"""Held-out domain examples/millshop under every strategy and fault level (helper heldout16).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).  The strategies are every name of
``nowplan.api.strategy_names()`` (a switch alone: ``hpn+<switch>``, ``online+<switch>`` for the
online policy's), with the four combinations of tests/test_matrix.py.

    PYTHONPATH=src:examples/millshop:benchmarks python benchmarks/heldout16.py --seeds 0-9 --time-limit 10 \
        --out benchmarks/results/heldout16/runs.jsonl

The level ``clean-heuristic`` (the belief offers its own ``planning_heuristic``) is not in the default
set; run it with ``--levels clean-heuristic --strategies flat,online,hpn``.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from typing import Any

from heldout12 import strategies  # benchmarks/heldout12.py: every switch alone, then the combinations
from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure; x exogenous change (a powered machine
# trips off, seen); the world's own faults: s a turn scraps the blank for good (irreversible), m a coat
# smudges the part (it must be stripped), l the report after an action is the one from before it (late)
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "clean": ("millshop", {}),
    "f0.2-s0.1-m0.2": ("millshop", {"failure_prob": 0.2, "scrap": 0.1, "smudge": 0.2}),
    "x0.2-l0.1-m0.1": ("millshop", {"exogenous_prob": 0.2, "lag": 0.1, "smudge": 0.1}),
    # beyond the benchmark's levels (a stress run, named apart): every fault at once, harder
    "stress-f0.2-x0.3-s0.2-m0.2-l0.2": ("millshop", {"failure_prob": 0.2, "exogenous_prob": 0.3, "scrap": 0.2,
                                                     "smudge": 0.2, "lag": 0.2}),
}
EXTRA_LEVELS = {"clean-heuristic": ("millshop", {"heuristic": True})}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from millshop_domain.scenarios import episode

    return {"millshop": episode}


if __name__ == "__main__":
    if "--strategies" not in sys.argv:
        sys.argv += ["--strategies", ",".join(strategies())]
    if "--levels" not in sys.argv:
        sys.argv += ["--levels", ",".join(LEVELS)]
    raise SystemExit(run_benchmark(__doc__ or "", {**LEVELS, **EXTRA_LEVELS}, episodes, 10.0))
