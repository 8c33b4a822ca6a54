"""Held-out domain examples/gridfix under every strategy and fault level (helper heldout17).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).  The strategies are every name of
``nowplan.api.strategy_names()`` (a switch alone: ``hpn+<switch>``, ``online+<switch>`` for the
online policy's), with the four combinations of tests/test_matrix.py.

    PYTHONPATH=src:examples/gridfix:benchmarks python benchmarks/heldout17.py --seeds 0-4 --time-limit 10 \
        --out benchmarks/results/heldout17/runs.jsonl
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from typing import Any

from heldout12 import strategies  # benchmarks/heldout12.py: every switch alone, then the combinations
from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure (a failed close looks like a trip: the
# belief takes it as evidence of a fault); x exogenous change (a gust breaks an intact segment: what it
# fed goes dead, seen on the telemetry, the segment not; or the battery drains a level, seen); the
# detector's own faults: m a missed fault (false negative), p a false alarm
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "clean": ("gridfix", {}),
    "m0.15-p0.1": ("gridfix", {"miss": 0.15, "fp": 0.1}),
    "f0.2-m0.1-p0.05": ("gridfix", {"failure_prob": 0.2, "miss": 0.1, "fp": 0.05}),
    "x0.15-m0.1-p0.05": ("gridfix", {"exogenous_prob": 0.15, "miss": 0.1, "fp": 0.05}),
    # beyond the benchmark's levels (a stress run, named apart): every fault at once, harder
    "stress-f0.2-x0.2-m0.2-p0.1": ("gridfix", {"failure_prob": 0.2, "exogenous_prob": 0.2, "miss": 0.2, "fp": 0.1}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from gridfix_domain.scenarios import episode

    return {"gridfix": episode}


if __name__ == "__main__":
    if "--strategies" not in sys.argv:
        sys.argv += ["--strategies", ",".join(strategies())]
    if "--levels" not in sys.argv:
        sys.argv += ["--levels", ",".join(LEVELS)]
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 10.0))
