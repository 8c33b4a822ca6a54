"""`nowplan plan` from two source trees, alternating, on benchmarks/classical's instances: cost and planning CPU.

Made for the anytime improvement's work budget (planning/anytime.py): each instance runs twice per tree
(order A B B A), so an instance whose two costs differ within one tree shows a load-dependent plan.

    python benchmarks/anytime_budget_ab.py --before OLD/src --after src --out FILE.jsonl
    python benchmarks/anytime_budget_ab.py --summarize FILE.jsonl

``OLD/src`` is e.g. ``git archive <commit> src | tar -x -C OLD`` with the compiled kernel copied in
(``cp src/nowplan/planning/_kernel*.so OLD/src/nowplan/planning/``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLASSICAL = ROOT / "benchmarks" / "classical"
CLI = "import sys; from nowplan.cli import main; sys.exit(main())"


def run(src: str, domain: Path, problem: Path, limit: float) -> tuple[float | None, float]:
    env = dict(os.environ, PYTHONPATH=src)
    out = subprocess.run([sys.executable, "-c", CLI, "plan", str(domain), str(problem), "--json",
                          "--time-limit", str(limit)], capture_output=True, text=True, env=env, check=False)
    doc = json.loads(out.stdout)
    return doc["cost"], doc["planning_cpu_s"]


def measure(before: str, after: str, out: Path, limit: float) -> None:
    with out.open("w") as f:
        for d in sorted(p for p in CLASSICAL.iterdir() if (p / "domain.pddl").is_file()):
            for p in sorted(d.glob("p0*.pddl")):
                row: dict[str, object] = {"inst": f"{d.name}/{p.name}", "before": [], "after": []}
                for name, src in (("before", before), ("after", after), ("after", after), ("before", before)):
                    row[name].append(run(src, d / "domain.pddl", p, limit))  # type: ignore[attr-defined]
                f.write(json.dumps(row) + "\n")
                f.flush()


def summarize(path: Path) -> str:
    rows = [json.loads(line) for line in path.read_text().splitlines()]

    def costs(r: dict[str, list[list[float]]], k: str) -> list[float]:
        return [c for c, _ in r[k]]

    def cpu(r: dict[str, list[list[float]]], k: str) -> float:
        return sum(t for _, t in r[k])

    lines = [f"{len(rows)} instances; instances whose two runs in one tree differ in cost: before "
             f"{sum(len(set(costs(r, 'before'))) > 1 for r in rows)}, after "
             f"{sum(len(set(costs(r, 'after'))) > 1 for r in rows)}"]
    ratio = [sum(costs(r, "after")) / sum(costs(r, "before")) for r in rows]
    lines.append(f"cost after/before (sum of the two runs): mean {statistics.mean(ratio):.3f}, min {min(ratio):.3f}, "
                 f"max {max(ratio):.3f}; cheaper on {sum(x < 1 for x in ratio)}, dearer on {sum(x > 1 for x in ratio)}")
    c = [cpu(r, "after") / cpu(r, "before") for r in rows]
    lines.append(f"planning CPU after/before: geometric mean {math.exp(statistics.mean(map(math.log, c))):.2f}, "
                 f"max {max(c):.2f}; summed {sum(cpu(r, 'before') for r in rows):.1f} s -> "
                 f"{sum(cpu(r, 'after') for r in rows):.1f} s")
    for r, x in zip(rows, ratio):
        if x != 1:
            lines.append(f"  {r['inst']}: costs before {costs(r, 'before')}, after {costs(r, 'after')}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--before", help="source tree (the src folder) of the first variant")
    ap.add_argument("--after", help="source tree of the second variant")
    ap.add_argument("--out", type=Path, help="JSONL file to write")
    ap.add_argument("--time-limit", type=float, default=20.0, help="`nowplan plan --time-limit` (20 s)")
    ap.add_argument("--summarize", type=Path, metavar="FILE", help="only summarize a stored JSONL file")
    args = ap.parse_args(argv)
    if args.summarize:
        print(summarize(args.summarize))
        return 0
    if not (args.before and args.after and args.out):
        ap.error("--before, --after and --out are needed (or --summarize FILE)")
    measure(args.before, args.after, args.out, args.time_limit)
    print(summarize(args.out))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
