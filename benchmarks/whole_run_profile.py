"""Where one whole run of a large PDDL instance spends its CPU: planning, set-up, garbage collection,
``State.apply``, and (``--profile``) a cProfile listing.

The instances are ``benchmarks/criticality_auto.py``'s largest tier (``--domain`` and ``--index`` pick
one), run as that script runs them (auto-HPN with ``--setting auto``, flat planning with ``flat``).
The figures of the 2026-12-04 session's commits (State per predicate, goal indexes, lazy plan records,
``Executive.holds_goal``) come from this:

    .venv/bin/python benchmarks/whole_run_profile.py --domain miconic --index 0 --setting auto
    .venv/bin/python benchmarks/whole_run_profile.py --domain gripper --index 0 --setting auto --profile 40

Compare two source trees by running each with ``PYTHONPATH=TREE/src`` one after the other, several
rounds (the machine is shared: ratios within a round, never absolute seconds across sessions).
"""

from __future__ import annotations

import argparse
import cProfile
import gc
import pstats
import tempfile
import time
from pathlib import Path
from typing import Any

import criticality_auto as ca  # benchmarks/criticality_auto.py, beside this script
from nowplan.core import state as state_mod


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--domain", required=True, choices=sorted(ca.LARGEST))
    ap.add_argument("--index", type=int, default=0, help="which of the domain's largest instances (0 or 1)")
    ap.add_argument("--setting", choices=("auto", "flat"), default="auto")
    ap.add_argument("--profile", type=int, default=0, help="print the N costliest functions (cumulative)")
    args = ap.parse_args(argv)
    params, seed = ca.LARGEST[args.domain][args.index]
    gc_time = [0.0, 0, 0.0]  # seconds, collections, start of the current one

    def on_gc(phase: str, info: dict[str, Any]) -> None:
        if phase == "start":
            gc_time[2] = time.process_time()
        else:
            gc_time[0] += time.process_time() - gc_time[2]
            gc_time[1] += 1

    applied = [0.0, 0]
    apply = state_mod.State.apply

    def timed_apply(self: Any, effects: Any) -> Any:
        t = time.process_time()
        out = apply(self, effects)
        applied[0] += time.process_time() - t
        applied[1] += 1
        return out

    with tempfile.TemporaryDirectory() as tmp:
        problem = Path(tmp) / "p.pddl"
        problem.write_text(ca.generate(args.domain, params, seed))
        state_mod.State.apply = timed_apply  # type: ignore[method-assign]
        gc.callbacks.append(on_gc)
        prof = cProfile.Profile() if args.profile else None
        try:
            if prof is not None:
                prof.enable()
            row = ca.run_one(ca.domain_file(args.domain), problem, "auto" if args.setting == "auto" else None,
                             "hpn" if args.setting == "auto" else "flat", 60.0, "forward")
            if prof is not None:
                prof.disable()
        finally:
            gc.callbacks.remove(on_gc)
            state_mod.State.apply = apply  # type: ignore[method-assign]
    print(f"{args.domain} {'-'.join(map(str, params.values()))} {args.setting}: {row['outcome']}, "
          f"whole run {row['total_cpu_s']:.3f} CPU s, planning {row['planning_cpu_s']:.3f}, "
          f"set-up {row['prep_cpu_s']:.3f}, collector {gc_time[0]:.3f} s in {gc_time[1]} collections, "
          f"State.apply {applied[0]:.3f} s in {applied[1]} calls, {row['actions']} actions")
    if prof is not None:
        pstats.Stats(prof).sort_stats("cumulative").print_stats(args.profile)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
