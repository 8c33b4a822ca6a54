"""Which pairs' automatic criticalities differ between two source trees (``--criticality auto`` as loaded).

Each tree runs in its own process (``PYTHONPATH=TREE/src``), loads every domain/problem pair of the
folders (``benchmarks/ipc_check.pairs``) with ``load_pddl(D, P, "auto")`` and prints the
criticality file of the loaded domain (``nowplan.io.criticality.criticality_text``); the pairs whose
texts differ are the ones a change of the hierarchy can affect (the others run the same criticalities).

    .venv/bin/python benchmarks/auto_crit_changes.py --before MAIN/src --after src /tmp/ipc8 /tmp/ipc9
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LOG = logging.getLogger("auto_crit_changes")

CHILD = """
import json, logging, sys
from pathlib import Path
logging.disable(logging.CRITICAL)
sys.path.insert(0, sys.argv[1])
from benchmarks.ipc_check import pairs
from nowplan.errors import NowplanError
from nowplan.io.criticality import criticality_text
from nowplan.io.pddl_read import load_pddl
out = {}
for folder in sys.argv[3:]:
    for name, dom, prob in pairs(Path(folder), int(sys.argv[2])):
        try:
            out[f"{Path(folder).name}/{name}"] = criticality_text(load_pddl(dom, prob, "auto").domain)
        except NowplanError as exc:
            out[f"{Path(folder).name}/{name}"] = f"refused: {type(exc).__name__}"
print(json.dumps(out))
"""


def texts(tree: Path, folders: list[Path], problems: int) -> dict[str, str]:
    env = {**os.environ, "PYTHONPATH": str(tree)}
    res = subprocess.run([sys.executable, "-c", CHILD, str(ROOT), str(problems), *map(str, folders)],
                         env=env, capture_output=True, text=True, timeout=1800, check=True)
    out: dict[str, str] = json.loads(res.stdout)
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", type=Path, nargs="+")
    ap.add_argument("--before", type=Path, required=True, help="a source tree's src/ folder")
    ap.add_argument("--after", type=Path, required=True)
    ap.add_argument("--problems", type=int, default=8, help="problems per domain folder (as auto_ipc.py)")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    a, b = texts(args.before, args.folders, args.problems), texts(args.after, args.folders, args.problems)
    changed = sorted(k for k in a.keys() | b.keys() if a.get(k) != b.get(k))
    LOG.info("%d pairs, %d with other criticalities: %s", len(a.keys() | b.keys()), len(changed),
             ", ".join(changed) or "none")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
