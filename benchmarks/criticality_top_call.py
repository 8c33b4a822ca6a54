"""auto-HPN's first (top-level) planner call against flat planning's one call, on the larger instances.

On small classical instances the first forward call of either setting is mostly grounding and
building the integer task, which both pay once; HPN's refinements then come on top.  This prints,
per larger instance of benchmarks/criticality_auto.py (LARGER), the CPU time of flat planning's
call and of auto-HPN's top-level call (each the first call of a fresh process's caches: a fresh
problem is loaded per setting, flat first), with the planner the benchmark uses (forward engine):
where the top call alone costs about as much as flat planning, no refinement scheme can make
auto-HPN's total lower.

    PYTHONPATH=src .venv/bin/python benchmarks/criticality_top_call.py [--domains gripper,miconic]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks.classical.generate import domain_file, generate  # noqa: E402
from benchmarks.criticality_auto import LARGER  # noqa: E402
from nowplan.belief.symbolic import SymbolicBelief  # noqa: E402
from nowplan.core.levels import LevelMap, flat_levels  # noqa: E402
from nowplan.io.pddl_read import load_pddl  # noqa: E402
from nowplan.planning.problem_hierarchy import prepare_problem  # noqa: E402
from nowplan.planning.config import PlannerConfig  # noqa: E402
from nowplan.planning.regression import plan  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--domains", default="", help="comma-separated domain names (default: all of LARGER)")
    args = ap.parse_args(argv)
    wanted = [d for d in args.domains.split(",") if d]
    cfg = PlannerConfig(engine="forward")
    print("| domain | instance | flat call CPU s (steps) | auto top call CPU s (steps) | top / flat |")
    print("|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for d, insts in LARGER.items():
            if wanted and d not in wanted:
                continue
            for k, (params, seed) in enumerate(insts, start=1):
                path = Path(tmp) / f"{d}-{k}.pddl"
                path.write_text(generate(d, params, seed))
                flat = load_pddl(domain_file(d), path, None)
                rf = plan(flat.domain, flat.objects, SymbolicBelief(flat.init), flat.goal, flat_levels(), cfg)
                auto = prepare_problem(load_pddl(domain_file(d), path, "auto"))
                first = auto.stages[0] if auto.stages else auto.goal  # the executive's root plans it first
                ra = plan(auto.domain, auto.objects, SymbolicBelief(auto.init), first,
                          LevelMap(auto.domain.top_level), cfg)
                name = "large-" + "-".join(str(v) for v in params.values())

                def cell(r: object) -> str:
                    p = getattr(r, "plan", None)
                    return f"{getattr(r, 'cpu_time_s'):.3f} ({len(p) if p is not None else '-'})"

                print(f"| {d} | {name} | {cell(rf)} | {cell(ra)} | {ra.cpu_time_s / rf.cpu_time_s:.2f} |",
                      flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
