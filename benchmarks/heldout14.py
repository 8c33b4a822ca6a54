"""Held-out domain examples/tidy under every strategy and fault level (helper heldout14).

One process, one run at a time; each run is guarded by SIGALRM (a hang is recorded, not waited
for).  Writes one JSON line per run and prints a table: level x strategy -> success %, mean
actions, failure reasons, crashes (benchmarks/heldout_runs.py).  The strategies are every name of
``nowplan.api.strategy_names()`` (a switch alone: ``hpn+<switch>``, ``online+<switch>`` for the
online policy's), with the four combinations of tests/test_matrix.py.

    PYTHONPATH=src:examples/tidy:benchmarks python benchmarks/heldout14.py --seeds 0-4 --time-limit 10 \
        --levels clean,f0.2-drop0.1,x0.15-drop0.05 --out benchmarks/results/heldout14/runs.jsonl

The level ``spots-clean`` (not a fault level: the house where a thing put aside goes to a spot a
generator proposes) is run apart, on a few strategies.
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Mapping
from typing import Any

from heldout12 import strategies  # benchmarks/heldout12.py: every switch alone, then the combinations
from heldout_runs import main as run_benchmark  # benchmarks/heldout_runs.py, beside this script

# name: (domain, scenario keyword arguments); f action failure, x exogenous change (the cat drags
# a clear thing to a floor spot of its room or the next, unseen unless the robot is there), drop
# the gripper's chance to drop what it carries on each move (seen)
LEVELS: dict[str, tuple[str, dict[str, Any]]] = {
    "clean": ("tidy", {}),
    "f0.2-drop0.1": ("tidy", {"failure_prob": 0.2, "drop": 0.1}),
    "x0.15-drop0.05": ("tidy", {"exogenous_prob": 0.15, "drop": 0.05}),
    "spots-clean": ("tidy", {"spots": True}),
}


def episodes() -> Mapping[str, Callable[..., Any]]:
    from tidy_domain.scenarios import episode

    return {"tidy": episode}


if __name__ == "__main__":
    if "--strategies" not in sys.argv:
        sys.argv += ["--strategies", ",".join(strategies())]
    if "--levels" not in sys.argv:
        sys.argv += ["--levels", "clean,f0.2-drop0.1,x0.15-drop0.05"]
    raise SystemExit(run_benchmark(__doc__ or "", LEVELS, episodes, 10.0))
