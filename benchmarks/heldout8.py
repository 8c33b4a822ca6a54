"""Held-out domains (examples/drone, examples/ward) under every strategy and fault level.

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: domain x level x strategy -> success %,
mean actions, failure reasons, crashes.

    PYTHONPATH=src:examples/drone:examples/ward python benchmarks/heldout8.py --seeds 0-19 --time-limit 20 \
        --out benchmarks/results/heldout8/runs.jsonl
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario function keyword arguments); f action failure, x exogenous change (drone: a
# gust the drone does not feel; ward: staff open/shut doors, push the trolley), n sensor noise (drone:
# the position fix's sigma; ward: a door misread), m missed detections (drone: no fix; ward: a door
# not read), slip the drone's own grasp fault
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "drone-clean": ("drone", {}),
    "drone-f0.2-slip0.1": ("drone", {"failure_prob": 0.2, "slip": 0.1}),
    "drone-x0.2-n0.15-m0.2": ("drone", {"exogenous_prob": 0.2, "fix_sigma": 0.15, "miss": 0.2, "slip": 0.2}),
    "drone-f0.5-x0.5-n0.3-m0.3": ("drone", {"failure_prob": 0.5, "exogenous_prob": 0.5, "fix_sigma": 0.3,
                                            "miss": 0.3}),
    "drone-three-f0.2-x0.2": ("drone", {"parcels": 3, "failure_prob": 0.2, "exogenous_prob": 0.2}),
    "ward-clean": ("ward", {}),
    "ward-f0.2": ("ward", {"failure_prob": 0.2}),
    "ward-x0.2-n0.1-m0.1": ("ward", {"exogenous_prob": 0.2, "noise": 0.1, "miss": 0.1}),
    "ward-x0.5": ("ward", {"exogenous_prob": 0.5}),
    "ward-f0.5-x0.5-n0.2-m0.3": ("ward", {"failure_prob": 0.5, "exogenous_prob": 0.5, "noise": 0.2, "miss": 0.3}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from drone_domain.scenarios import episode as drone_episode
    from ward_domain.scenarios import episode as ward_episode

    return {"drone": drone_episode, "ward": ward_episode}


if __name__ == "__main__":
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 20.0))
