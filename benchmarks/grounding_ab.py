"""A/B of the grounder (planning/task_grounding.py) between two source trees, alternating.

For each DOMAIN.pddl PROBLEM.pddl pair and round, grounds the problem flat at levels -1 and 0 with
the tree ``--before`` and then with ``--after`` (each in its own process, ``PYTHONPATH=TREE``), and
prints one JSON line: tree, problem, the CPU s of the two groundings, the number of actions and a
digest of the action keys and reached atoms (equal digests: the same grounding).

    git archive OLD src | tar -x -C /tmp/old && cp src/nowplan/planning/_kernel*.so /tmp/old/src/nowplan/planning/
    .venv/bin/python benchmarks/grounding_ab.py --before /tmp/old/src --after src --rounds 2 \\
        /tmp/ipc8/tidybot-sat11/{domain,p04}.pddl /tmp/ipc8/parking-sat11/{domain,p07}.pddl > runs.jsonl
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

CHILD = """
import hashlib, json, sys, time
from nowplan.io.pddl_read import load_pddl
import nowplan.planning.task_grounding as tg
p = load_pddl(sys.argv[1], sys.argv[2])
init = {a for a in p.init.atoms() if a.value is True}
cpu, keys, n = 0.0, [], 0
for level in sorted({-1, p.domain.top_level}):
    c0 = time.process_time()
    g = tg._ground(p.domain, p.objects, init, p.domain.static_predicates, level, None)
    cpu += time.process_time() - c0
    n = len(g.actions)
    keys.append((sorted(repr(a.key) for a in g.actions), sorted(map(repr, g.reached))))
print(json.dumps({"cpu_s": round(cpu, 3), "actions": n,
                  "digest": hashlib.sha1(repr(keys).encode()).hexdigest()[:10]}))
"""


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--before", type=Path, required=True, help="source tree (the folder holding nowplan/)")
    ap.add_argument("--after", type=Path, required=True)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("files", nargs="+", type=Path, help="DOMAIN PROBLEM pairs")
    args = ap.parse_args()
    if len(args.files) % 2:
        ap.error("give DOMAIN PROBLEM pairs")
    pairs = list(zip(args.files[::2], args.files[1::2], strict=True))
    for r in range(args.rounds):
        for dom, prob in pairs:
            for name, tree in (("before", args.before), ("after", args.after)):
                env = {**os.environ, "PYTHONPATH": str(tree.resolve())}
                out = subprocess.run([sys.executable, "-c", CHILD, str(dom), str(prob)], env=env,
                                     capture_output=True, text=True, check=True, timeout=600).stdout
                row = {"round": r, "tree": name, "problem": f"{dom.parent.name}/{prob.stem}",
                       **json.loads(out.strip().splitlines()[-1]), "load": round(os.getloadavg()[0], 2)}
                print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
