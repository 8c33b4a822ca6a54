"""Held-out domains (examples/lab, examples/search) under every strategy and fault level.

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: domain x level x strategy -> success %,
mean actions, failure reasons, crashes.

    PYTHONPATH=src:examples/lab:examples/search python benchmarks/heldout7.py --seeds 0-19 \
        --out benchmarks/results/heldout7/runs.jsonl
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario function keyword arguments)
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "lab-clean": ("lab", {}),
    "lab-f0.2-sticky0.3": ("lab", {"failure_prob": 0.2, "sticky": 0.3}),
    "lab-x0.2": ("lab", {"exogenous_prob": 0.2}),
    "lab-f0.5-x0.5": ("lab", {"failure_prob": 0.5, "exogenous_prob": 0.5, "sticky": 0.3}),
    "lab-f0.6": ("lab", {"failure_prob": 0.6, "sticky": 0.3}),
    "lab-two-f0.2-x0.2": ("lab", {"failure_prob": 0.2, "exogenous_prob": 0.2, "samples": 2}),
    "search-clean": ("search", {}),
    "search-m0.3": ("search", {"miss": 0.3}),
    "search-f0.2-m0.2": ("search", {"failure_prob": 0.2, "miss": 0.2}),
    "search-x0.2-m0.1": ("search", {"exogenous_prob": 0.2, "miss": 0.1}),
    "search-f0.5-x0.5-m0.3": ("search", {"failure_prob": 0.5, "exogenous_prob": 0.5, "miss": 0.3}),
    "search-f0.6-m0.4": ("search", {"failure_prob": 0.6, "miss": 0.4}),
    "search-three-m0.2": ("search", {"miss": 0.2, "wanted": 3}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from lab_domain.scenarios import episode as lab_episode
    from search_domain.scenarios import episode as search_episode

    return {"lab": lab_episode, "search": search_episode}


if __name__ == "__main__":
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 30.0))
