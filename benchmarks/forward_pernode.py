"""Per-node speed of the forward search (issue 19, target 5): the C kernel against the Python loop.

For each instance of benchmarks/classical (or --domains / --instances), the
task is grounded once and then searched by each of: LAMA in the kernel, LAMA
in Python (``NOWPLAN_PURE_PYTHON=1``, the loop `--search lama` ran before the
kernel had it), GBFS in the kernel.  Both LAMA paths must give the same plan
and counters (the script stops otherwise).  Search CPU time
(``time.process_time``) and expansions give nodes/s; compare the columns
within one run.  Writes forward_pernode.csv and forward_pernode.md into --out.

    PYTHONPATH=src .venv/bin/python benchmarks/forward_pernode.py [--domains logistics,driverlog]
        [--instances 1-5] [--out benchmarks/results/forward_pernode]
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):  # this checkout's nowplan and benchmarks package
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks.classical.generate import DOMAINS, domain_file, instance_files  # noqa: E402
from nowplan.core.levels import flat_levels  # noqa: E402
from nowplan.io.pddl_read import load_pddl  # noqa: E402
from nowplan.planning import forward, native  # noqa: E402
from nowplan.planning.task import Task, build_task  # noqa: E402

RUNS = (("lama", "c"), ("lama", "python"), ("gbfs", "c"))


def _numbers(spec: str) -> list[int]:
    out: list[int] = []
    for part in spec.split(","):
        lo, _, hi = part.partition("-")
        out += range(int(lo), int(hi or lo) + 1)
    return out


def timed_search(task: Task, method: str, path: str) -> tuple[forward.ForwardResult, float]:
    os.environ[native.ENV] = "1" if path == "python" else "0"
    t0 = time.process_time()
    res = forward.search(task, method=method)  # type: ignore[arg-type]
    return res, time.process_time() - t0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--domains", default=",".join(DOMAINS))
    ap.add_argument("--instances", default="", help="instance numbers, e.g. 1-3,5 (default: all)")
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "forward_pernode")
    args = ap.parse_args(argv)
    if native.kernel_class() is None:
        raise SystemExit("forward_pernode: the compiled kernel is not built (pip install -e .)")
    wanted = set(_numbers(args.instances)) if args.instances else None
    rows: list[dict[str, Any]] = []
    for d in args.domains.split(","):
        for prob in instance_files(d):
            if wanted is not None and int(prob.stem[1:]) not in wanted:
                continue
            p = load_pddl(str(domain_file(d)), str(prob))
            task = build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: a.cost(p.init))
            row: dict[str, Any] = {"domain": d, "instance": prob.stem}
            seen: dict[str, tuple[Any, ...]] = {}
            for method, path in RUNS:
                res, cpu = timed_search(task, method, path)
                key = f"{method}_{path}"
                row[f"{key}_expanded"] = res.expanded
                row[f"{key}_cpu_s"] = round(cpu, 5)
                row[f"{key}_nodes_per_s"] = round(res.expanded / cpu) if cpu > 0 else ""
                summary = (res.status, [str(a) for a in res.actions or []], res.expanded, res.generated,
                           res.evaluated)
                if method in seen and seen[method] != summary:
                    raise SystemExit(f"forward_pernode: {d} {prob.stem}: {method} differs between paths")
                seen[method] = summary
            rows.append(row)
            print(d, prob.stem, {k: v for k, v in row.items() if k.endswith(("nodes_per_s", "expanded"))},
                  file=sys.stderr, flush=True)
    args.out.mkdir(parents=True, exist_ok=True)
    with open(args.out / "forward_pernode.csv", "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    (args.out / "forward_pernode.md").write_text(markdown(rows, argv if argv is not None else sys.argv[1:]))
    print((args.out / "forward_pernode.md").read_text())
    return 0


def markdown(rows: list[dict[str, Any]], argv: list[str]) -> str:
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                            check=False).stdout.strip()
    lines = [
        "# Forward search per node: C kernel against the Python loop",
        "",
        f"`benchmarks/forward_pernode.py {' '.join(argv)}` at commit {commit}. Search CPU only (the task is "
        "grounded once, before); nodes/s = expansions / search CPU s, summed over a domain's instances. "
        "LAMA gives the same plan and counters on both paths.",
        "",
        "| domain | expanded (lama) | lama C nodes/s | lama Python nodes/s | C / Python | gbfs C nodes/s |",
        "|---|---|---|---|---|---|",
    ]
    ratios = []

    def rate(rs: list[dict[str, Any]], key: str) -> float:
        cpu = sum(r[f"{key}_cpu_s"] for r in rs)
        return sum(r[f"{key}_expanded"] for r in rs) / cpu if cpu > 0 else math.nan

    groups: dict[str, list[dict[str, Any]]] = {}
    for r in rows:
        groups.setdefault(r["domain"], []).append(r)
    groups["**all**"] = rows
    for d, rs in groups.items():
        c, py, g = rate(rs, "lama_c"), rate(rs, "lama_python"), rate(rs, "gbfs_c")
        if d != "**all**":
            ratios.append(c / py)
        lines.append(f"| {d} | {sum(r['lama_c_expanded'] for r in rs)} | {c:,.0f} | {py:,.0f} | {c / py:.1f}× "
                     f"| {g:,.0f} |")
    lines += ["", f"Per domain, C / Python: from {min(ratios):.1f}× to {max(ratios):.1f}×.", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    raise SystemExit(main())
