"""Held-out domain examples/ferry under every strategy and fault level (helper heldout15).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).  The strategies are every name of
``nowplan.api.strategy_names()`` (a switch alone: ``hpn+<switch>``, ``online+<switch>`` for the
online policy's), with the four combinations of tests/test_matrix.py.

    PYTHONPATH=src:examples/ferry:benchmarks python benchmarks/heldout15.py --seeds 0-4 --time-limit 10 \
        --out /tmp/heldout15/runs.jsonl
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from typing import Any

from heldout12 import strategies  # benchmarks/heldout12.py: every switch alone, then the combinations
from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure, b a passenger balks at boarding (a
# fault of the world's own), x exogenous change (a passenger not yet served wants another dock, seen)
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "clean": ("ferry", {}),
    "f0.2-b0.2": ("ferry", {"failure_prob": 0.2, "balk": 0.2}),
    "x0.2-b0.1": ("ferry", {"exogenous_prob": 0.2, "balk": 0.1}),
    # beyond the benchmark's levels (a stress run, named apart): all three faults at once, harder
    "stress-f0.2-x0.4-b0.3": ("ferry", {"failure_prob": 0.2, "exogenous_prob": 0.4, "balk": 0.3}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from ferry_domain.scenarios import episode

    return {"ferry": episode}


if __name__ == "__main__":
    if "--strategies" not in sys.argv:
        sys.argv += ["--strategies", ",".join(strategies())]
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 10.0))
