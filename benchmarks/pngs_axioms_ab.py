"""A/B: ``nowplan plan`` with two source trees, alternated, on domain/problem pairs (the anytime budget change).

Each run is a process with ``PYTHONPATH`` set to one tree's ``src``; it prints per run the plan's cost,
length, the first search's expansions and the planner's CPU seconds (``--json``), and whether the two trees'
plans are the same.  Runs alternate A, B, A, B per pair so the machine's load falls on both alike.

    .venv/bin/python benchmarks/pngs_axioms_ab.py OLD/src src DOMAIN PROBLEM [DOMAIN PROBLEM ...] [--reps 2]
"""

from __future__ import annotations

import argparse
import compileall
import json
import os
import subprocess
import sys

CLI = "import sys; from nowplan.cli import main; raise SystemExit(main(sys.argv[1:]))"


def run(src: str, dom: str, prob: str) -> dict[str, object]:
    env = {**os.environ, "PYTHONPATH": src}
    out = subprocess.run([sys.executable, "-c", CLI, "plan", dom, prob, "--json", "--time-limit", "60"],
                         env=env, capture_output=True, text=True, timeout=180)
    try:
        data: dict[str, object] = json.loads(out.stdout)
    except json.JSONDecodeError:
        return {"status": f"exit {out.returncode}", "plan": []}
    return data


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("pairs", nargs="+")
    ap.add_argument("--reps", type=int, default=2)
    args = ap.parse_args()
    for src in (args.a, args.b):  # bytecode once, as `pip install` does (else each run compiles the lazy imports)
        compileall.compile_dir(src, quiet=1)
    same = diff = 0
    for dom, prob in zip(args.pairs[::2], args.pairs[1::2]):
        for rep in range(args.reps):
            res = {tag: run(src, dom, prob) for tag, src in (("A", args.a), ("B", args.b))}
            for tag, r in res.items():
                plan = r.get("plan") or []
                assert isinstance(plan, list)
                print(f"{prob} rep {rep} {tag}: {r.get('status')} cost {r.get('cost')} steps {len(plan)} "
                      f"expanded {r.get('expanded')} planner CPU {r.get('planning_cpu_s')} s")
            if res["A"].get("plan") == res["B"].get("plan"):
                same += 1
            else:
                diff += 1
    print(f"same plan {same}, different {diff}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
