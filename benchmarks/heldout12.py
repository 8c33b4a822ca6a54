"""Held-out domain examples/greenhouse under every strategy and fault level (helper heldout12).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).  The strategies are every name of
``nowplan.api.strategy_names()`` (a switch alone: ``hpn+<switch>``, ``online+<switch>`` for the
online policy's), with the four combinations of tests/test_matrix.py.

    PYTHONPATH=src:examples/greenhouse:benchmarks python benchmarks/heldout12.py --seeds 0-9 --time-limit 20 \
        --out benchmarks/results/heldout12/runs.jsonl
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from typing import Any

from nowplan.api import strategy_names

from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure, x exogenous change (the tank leaks
# a level, or pests land on an unwatered plant, unseen), n the pest sensor's error rate
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "small-clean": ("greenhouse", {"size": "small"}),
    "small-f0.2-n0.1": ("greenhouse", {"size": "small", "failure_prob": 0.2, "noise": 0.1}),
    "small-x0.2-n0.2": ("greenhouse", {"size": "small", "exogenous_prob": 0.2, "noise": 0.2}),
    "medium-f0.2-x0.1-n0.1": ("greenhouse", {"size": "medium", "failure_prob": 0.2, "exogenous_prob": 0.1,
                                             "noise": 0.1}),
}
ONLINE = ("reuse", "deferred")
COMBOS = ["hpn+flexible+serendipity+selective+foresight", "flat+flexible+serendipity", "hpn+peephole+flexible",
          "online+reuse+deferred"]


def strategies() -> list[str]:
    """Every switch of ``strategy_names()`` as a strategy of its own, then the combinations."""
    out = [s if s in ("hpn", "flat", "online") else f"online+{s}" if s in ONLINE else f"hpn+{s}"
           for s in strategy_names()]
    return out + COMBOS


def episodes() -> Mapping[str, Callable[..., Any]]:
    from greenhouse_domain.scenarios import episode

    return {"greenhouse": episode}


if __name__ == "__main__":
    if "--strategies" not in sys.argv:
        sys.argv += ["--strategies", ",".join(strategies())]
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 20.0))
