"""Where a whole run's CPU goes, flat vs ``--criticality auto`` (issue 18), on the larger instances.

For each instance (``DOMAIN:K``: the K-th of ``criticality_auto.LARGER[DOMAIN]``) and setting, runs
``criticality_auto.run_one`` twice in this process (the first warms imports; grounding caches are
cleared before each run) and reports, for the second, the run's totals (whole run, planner calls,
``prepare_problem``) and the CPU inside a few functions, timed by wrapping them (process_time;
nested phases overlap: ``build_task`` contains ``build_structure``, ``make_plan`` the planner's).

    PYTHONPATH=src .venv/bin/python benchmarks/criticality_auto_phases.py depots:1 miconic:2 satellite:L1

``DOMAIN:LK`` names the K-th of ``criticality_auto.LARGEST[DOMAIN]`` (the largest tier).
"""

from __future__ import annotations

import collections
import functools
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks.classical.generate import domain_file, generate  # noqa: E402
from benchmarks import criticality_auto  # noqa: E402
from benchmarks.criticality_auto import LARGER, LARGEST, run_one  # noqa: E402
from nowplan.acting import hpn, refine_flat  # noqa: E402
from nowplan.planning import dead_ends, forward, hff, landmarks, reach_statics, task, task_grounding  # noqa: E402
from nowplan.worlds import base  # noqa: E402

SPENT: collections.Counter[str] = collections.Counter()
CALLS: collections.Counter[str] = collections.Counter()

PHASES: list[tuple[Any, str, str]] = [
    (task_grounding, "_ground", "ground"), (task, "_build_structure", "build_structure"),
    (forward, "build_task", "build_task"), (forward, "search", "search"),
    (hpn.Executive, "make_plan", "make_plan"), (hpn.Executive, "direct_plan", "direct_plan"),
    (hpn.Executive, "push", "push"), (hpn.Executive, "execute", "execute"),
    (hpn.Executive, "applicable", "applicable"), (hpn.Executive, "watch", "watch"),
    (refine_flat.FlatSteps, "check_cycle", "check_cycle"), (base.SimulatedWorld, "execute", "world.execute"),
    (criticality_auto, "load_pddl", "parse"), (criticality_auto, "prepare_problem", "prepare_problem"),
    (reach_statics, "add_reachability_statics", "reach_statics"), (dead_ends, "irreversible_step", "dead_end_test"),
    (hff.RelaxedHeuristic, "__init__", "hff_init"), (landmarks.LandmarkCount, "__init__", "landmark_count_init"),
    (forward, "eliminate_actions", "eliminate_actions"),
]


def _timed(owner: Any, name: str, label: str) -> None:
    f = owner.__dict__[name]

    @functools.wraps(f)
    def g(*args: Any, **kwargs: Any) -> Any:
        t = time.process_time()
        try:
            return f(*args, **kwargs)
        finally:
            SPENT[label] += time.process_time() - t
            CALLS[label] += 1

    setattr(owner, name, g)


def main(argv: list[str]) -> int:
    for owner, name, label in PHASES:
        _timed(owner, name, label)
    with tempfile.TemporaryDirectory() as tmp:
        for spec in argv:
            d, k = spec.split(":")
            params, seed = LARGEST[d][int(k[1:]) - 1] if k.startswith("L") else LARGER[d][int(k) - 1]
            path = Path(tmp) / f"{d}-{k}.pddl"
            path.write_text(generate(d, params, seed))
            for setting, crit, strat in (("flat", None, "flat"), ("auto", "auto", "hpn+refine-flat")):
                run_one(domain_file(d), path, crit, strat, 60.0, "forward")
                SPENT.clear()
                CALLS.clear()
                r = run_one(domain_file(d), path, crit, strat, 60.0, "forward")
                phases = " ".join(f"{n}={v:.3f}/{CALLS[n]}" for n, v in SPENT.most_common())
                print(f"{spec} {setting} {r['outcome']} whole {r['total_cpu_s']:.3f} planning {r['planning_cpu_s']:.3f} "
                      f"prep {r['prep_cpu_s']:.3f} | {phases}", flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
