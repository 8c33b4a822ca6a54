"""Held-out domain examples/warehouse under every strategy and fault level (issue 14, helper heldout9).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).

    PYTHONPATH=src:examples/warehouse python benchmarks/heldout9.py --seeds 0-9 --time-limit 20 \
        --out benchmarks/results/heldout9/runs.jsonl
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure, x exogenous change (a worker moves
# a top box to another shelf slot, unseen unless the robot is there), m a slot's scan missed,
# fp a label misread as another box's (a false positive), frag the fragile box's pick fails
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "small-clean": ("warehouse", {"size": "small"}),
    "medium-f0.2-frag0.3": ("warehouse", {"size": "medium", "failure_prob": 0.2, "fragile": 0.3}),
    "medium-x0.2-m0.2-fp0.1": ("warehouse", {"size": "medium", "exogenous_prob": 0.2, "miss": 0.2, "false_pos": 0.1,
                                             "fragile": 0.3}),
    "hard-f0.2-x0.2-m0.1-fp0.05": ("warehouse", {"size": "hard", "failure_prob": 0.2, "exogenous_prob": 0.2,
                                                 "miss": 0.1, "false_pos": 0.05, "fragile": 0.3}),
    "medium-f0.5-x0.5-m0.3-fp0.2": ("warehouse", {"size": "medium", "failure_prob": 0.5, "exogenous_prob": 0.5,
                                                  "miss": 0.3, "false_pos": 0.2, "fragile": 0.5}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from warehouse_domain.scenarios import episode

    return {"warehouse": episode}


if __name__ == "__main__":
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 20.0))
