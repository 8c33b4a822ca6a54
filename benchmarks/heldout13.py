"""Held-out domain examples/mine under every strategy and fault level (helper heldout13).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).  The strategies are every name of
``nowplan.api.strategy_names()`` (a switch alone: ``hpn+<switch>``, ``online+<switch>`` for the
online policy's), with the four combinations of tests/test_matrix.py.

    PYTHONPATH=src:examples/mine:benchmarks python benchmarks/heldout13.py --seeds 0-9 --time-limit 10 \
        --out benchmarks/results/heldout13/runs.jsonl
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from typing import Any

from heldout12 import strategies  # benchmarks/heldout12.py: every switch alone, then the combinations
from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure, x exogenous change (the battery
# drains a level, or the draught opens the gate, both seen), m the detector's misses, fp its false beeps
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "clean": ("mine", {}),
    "f0.2-m0.1-fp0.1": ("mine", {"failure_prob": 0.2, "miss": 0.1, "fp": 0.1}),
    "x0.2-m0.2-fp0.1": ("mine", {"exogenous_prob": 0.2, "miss": 0.2, "fp": 0.1}),
    # beyond the benchmark's levels (a stress run, named apart): every fault at once, harder
    "stress-f0.3-x0.3-m0.3-fp0.2": ("mine", {"failure_prob": 0.3, "exogenous_prob": 0.3, "miss": 0.3, "fp": 0.2}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from mine_domain.scenarios import episode

    return {"mine": episode}


if __name__ == "__main__":
    if "--strategies" not in sys.argv:
        sys.argv += ["--strategies", ",".join(strategies())]
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 10.0))
