"""A/B on the held-out example domains: HPN's calls as by default (regression at abstract levels, an
abstract action at its own cost) against every level forward with hidden costs (``PlannerConfig(
engine="forward", hidden_costs=True)``: an abstract action costs its own cost plus ``h_max`` of the
preconditions its level hides; planning/hidden_costs.py).  One JSON line per domain x strategy x
setting: runs reached of seeds 0-4, mean actions and cost of the reached runs, planning CPU summed,
and what the others ended with (a refusal: the forward engine does not apply to that belief or domain).

    PYTHONPATH=src .venv/bin/python benchmarks/abstract_costs_ab.py > benchmarks/results/abstract_costs_ab/runs.jsonl

``--forward-alone``: the forward engine without hidden costs only (which of the two made a difference).
"""

from __future__ import annotations

import importlib
import json
import signal
import sys
from dataclasses import replace
from pathlib import Path
from typing import Any

from nowplan.api import parse_strategy, run_episode

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
# each example's scenario keyword arguments (the smallest size where there are sizes)
DOMAINS: dict[str, dict[str, Any]] = {
    "ferry": {}, "mine": {}, "tidy": {}, "warehouse": {"size": "small"}, "greenhouse": {"size": "small"},
    "lab": {}, "search": {}, "ward": {}, "house": {}, "drone": {},
}
SETTINGS: dict[str, dict[str, Any]] = {"default": {}, "forward+hidden": {"engine": "forward", "hidden_costs": True}}
FORWARD_ALONE: dict[str, dict[str, Any]] = {"forward": {"engine": "forward"}}  # which of the two did it
HANG_S = 40


def _alarm(*_: Any) -> None:
    raise TimeoutError


def main() -> int:
    signal.signal(signal.SIGALRM, _alarm)
    settings = FORWARD_ALONE if "--forward-alone" in sys.argv[1:] else SETTINGS
    for dom, kw in DOMAINS.items():
        sys.path.insert(0, str(EXAMPLES / dom))  # the example package, as a user's plugin is found
        episode = importlib.import_module(f"{dom}_domain.scenarios").episode
        for strat in ("hpn", "hpn+peephole"):
            for name, over in settings.items():
                res: list[tuple[str, int, float, float]] = []
                for seed in range(5):
                    s = parse_strategy(strat, max_actions=300, time_limit=20.0)
                    s = replace(s, planner=replace(s.planner, **over))
                    signal.alarm(HANG_S)
                    try:
                        m = run_episode(episode(seed=seed, **kw), s, seed=seed)
                        res.append((m.outcome.value, m.actions, m.execution_cost, m.planning_cpu_s))
                    except TimeoutError:
                        res.append(("hang", 0, 0.0, float(HANG_S)))
                    except Exception as e:  # noqa: BLE001 (a refusal is a row, not the end of the sweep)
                        res.append((f"{type(e).__name__}: {str(e)[:80]}", 0, 0.0, 0.0))
                    finally:
                        signal.alarm(0)
                ok = [r for r in res if r[0] == "reached"]
                print(json.dumps({
                    "domain": dom, "strategy": strat, "setting": name, "reached": len(ok),
                    "mean_actions": round(sum(r[1] for r in ok) / max(1, len(ok)), 1),
                    "mean_cost": round(sum(r[2] for r in ok) / max(1, len(ok)), 1),
                    "plan_cpu": round(sum(r[3] for r in res), 2),
                    "other": sorted({r[0][:90] for r in res if r[0] != "reached"})}), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
