"""Classical STRIPS benchmark (issue 19): `nowplan plan` against Fast Downward lama-first.

For every checked-in instance benchmarks/classical/<domain>/pNN.pddl, runs
(a) `nowplan plan DOMAIN PROBLEM --json` as a subprocess (the CLI's default
engine; its `method` is recorded) and then (b) Fast Downward's driver from the
up_fast_downward package with `--alias lama-first`, one after the other, each
killed at the time limit; wall times include the process start (nowplan's
sources are byte-compiled first, as an installed package is).  Every plan is
replayed in nowplan's core model (preconditions and goal); an invalid plan
counts as unsolved.  Writes classical.csv (one row per instance x planner),
classical_meta.json (command, commit, machine, elapsed time) and classical.md
(the per-domain summary and the targets, computed from the CSV) into --out.

    PYTHONPATH=src .venv/bin/python benchmarks/classical.py [--domains gripper,rovers]
        [--instances 1-3] [--time-limit 30] [--out benchmarks/results/classical]
    PYTHONPATH=src .venv/bin/python benchmarks/classical.py --summarize [--out DIR]
"""

from __future__ import annotations

import argparse
import compileall
import datetime
import json
import logging
import os
import platform
import shlex
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):  # this checkout's nowplan and benchmarks package
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks.classical.generate import DOMAINS, domain_file, instance_files, write_instances  # noqa: E402
from benchmarks.classical.harness import Run, check_plan, fd_driver, run_fd, run_nowplan  # noqa: E402
from benchmarks.classical.summary import FD, OURS, markdown, read_csv, write_csv  # noqa: E402
from nowplan.experiments import progress  # noqa: E402

OUT = ROOT / "benchmarks" / "results" / "classical"
log = logging.getLogger("classical")


def _numbers(text: str) -> list[int]:
    """``"1-3,5"`` → ``[1, 2, 3, 5]``; ``p02`` is accepted for 2."""
    out: list[int] = []
    for part in text.split(","):
        part = part.strip().lower().removeprefix("p")
        if not part:
            continue
        lo, sep, hi = part.partition("-")
        try:
            out += list(range(int(lo), int(hi.lstrip("p")) + 1)) if sep else [int(lo)]
        except ValueError:
            raise SystemExit(f"classical: expected instance numbers like 1-3,5, got '{text}'") from None
    return out


def _commit() -> str:
    def git(*args: str) -> str:
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=False).stdout.strip()

    head = git("rev-parse", "--short", "HEAD") or "unknown"
    return head + ("+dirty" if git("status", "--porcelain", "--", "src", "benchmarks/classical") else "")


def _row(domain: str, problem: Path, run: Run) -> dict[str, Any]:
    solved, status, cost, valid = run.solved, run.status, None, ""
    if run.solved:
        ok, msg, cost = check_plan(domain_file(domain), problem, run.plan)
        valid = str(ok)
        if not ok:
            solved, status, cost = False, f"invalid plan: {msg}", None
            log.warning("%s %s: %s returned an invalid plan: %s", domain, problem.name, run.planner, msg)
        elif run.cost is not None and cost is not None and abs(run.cost - cost) > 1e-6:
            log.warning("%s %s: %s reports cost %g, the replay gives %g", domain, problem.name, run.planner,
                        run.cost, cost)
    return {"domain": domain, "instance": problem.stem, "planner": run.planner, "solved": solved,
            "wall_s": round(run.wall_s, 4), "cost": cost, "expansions": run.expansions, "method": run.method,
            "status": status, "planning_s": run.planning_s, "valid": valid, "cpu_s": run.cpu_s,
            "evaluated": run.evaluated}


def _describe(r: dict[str, Any]) -> str:
    if not r["solved"]:
        return f"{r['planner']} {r['status']} ({r['wall_s']:.2f} s)"
    return f"{r['planner']} {r['wall_s']:.2f} s cost {r['cost']:g} expanded {r['expansions']}"


def run_all(tasks: list[tuple[str, Path]], limit: float, memory_mb: int | None, extra: list[str]) -> list[dict[str, Any]]:
    bar: Any = None
    if progress.wanted(sys.stderr):  # a terminal (or NOWPLAN_PROGRESS=1): a bar, else a line per instance
        bar = progress.bar(len(tasks), "classical", unit="instance")
    rows: list[dict[str, Any]] = []
    for domain, problem in tasks:
        if bar is not None:
            bar.set_description(f"{domain} {problem.stem}")
        dom = domain_file(domain)
        ours = _row(domain, problem, run_nowplan(dom, problem, limit, extra=extra, memory_mb=memory_mb))
        theirs = _row(domain, problem, run_fd(dom, problem, limit, memory_mb=memory_mb))
        rows += [ours, theirs]
        line = f"{domain} {problem.stem}: {_describe(ours)} | {_describe(theirs)}"
        if bar is not None:
            bar.write(line)
            bar.update()
        else:
            print(line, file=sys.stderr, flush=True)
    if bar is not None:
        bar.close()
    return rows


def _merge(dirs: list[Path], out: Path) -> int:
    rows: list[dict[str, Any]] = []
    metas: list[dict[str, Any]] = []
    for d in dirs:
        if not (d / "classical.csv").is_file():
            raise SystemExit(f"classical: no stored runs at {d / 'classical.csv'}")
        rows += read_csv(d / "classical.csv")
        if (d / "classical_meta.json").is_file():
            metas.append(json.loads((d / "classical_meta.json").read_text()))
    meta: dict[str, Any] = dict(metas[0]) if metas else {}
    if metas:
        meta["command"] = " ; ".join(m.get("command", "") for m in metas)
        meta["commit"] = ", ".join(sorted({str(m.get("commit")) for m in metas}))
        meta["elapsed_s"] = round(sum(float(m.get("elapsed_s") or 0) for m in metas), 1)
        meta["date"] = f"{metas[0].get('date', '')} to {metas[-1].get('date', '')}"
        loads = [x for m in metas for k in ("load_before", "load_after") if m.get(k) for x in m[k][:1]]
        meta.pop("load_before", None)
        meta.pop("load_after", None)
        meta["load_range"] = [min(loads), max(loads)] if loads else None
        meta["parts"] = metas
    out.mkdir(parents=True, exist_ok=True)
    write_csv(rows, out / "classical.csv")
    (out / "classical_meta.json").write_text(json.dumps(meta, indent=2) + "\n")
    text = markdown(read_csv(out / "classical.csv"), meta)
    (out / "classical.md").write_text(text)
    print(text)
    return 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=(__doc__ or "").splitlines()[0])
    ap.add_argument("--domains", default=",".join(DOMAINS), help=f"comma-separated, of {', '.join(DOMAINS)}")
    ap.add_argument("--instances", default="", help="instance numbers, e.g. 1-3,5 (default: all)")
    ap.add_argument("--time-limit", type=float, default=30.0, help="wall seconds per planner and instance (30)")
    ap.add_argument("--memory-limit", type=int, default=4096, metavar="MB",
                    help="address-space limit of each planner process, MB (4096; 0: none)")
    ap.add_argument("--nowplan-args", default="", help="extra arguments for `nowplan plan`, one string")
    ap.add_argument("--out", type=Path, default=OUT, help=f"output directory (default {OUT.relative_to(ROOT)})")
    ap.add_argument("--summarize", action="store_true", help="only rewrite classical.md from the stored CSV")
    ap.add_argument("--scale", action="store_true",
                    help="run the scale-up set (generate.SCALE, IPC mid-range sizes, s01-s05) instead of the "
                         "checked-in p01-p05; generated into --scale-dir or a temporary directory")
    ap.add_argument("--scale-dir", type=Path, default=None, help="where --scale writes its instances")
    ap.add_argument("--merge", type=Path, nargs="+", metavar="DIR",
                    help="combine the stored runs of these --out directories (e.g. one per domain, each "
                         "command under 10 minutes) into --out: one CSV, their metadata listed")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING, format="%(levelname)s %(name)s: %(message)s")
    csv_path, meta_path, md_path = (args.out / n for n in ("classical.csv", "classical_meta.json", "classical.md"))
    if args.merge:
        return _merge(args.merge, args.out)
    if args.summarize:
        if not csv_path.is_file():
            raise SystemExit(f"classical: no stored runs at {csv_path}; run the benchmark first")
        meta = json.loads(meta_path.read_text()) if meta_path.is_file() else {}
        text = markdown(read_csv(csv_path), meta)
        md_path.write_text(text)
        print(text)
        return 0
    domains = [d for d in args.domains.split(",") if d]
    bad = [d for d in domains if d not in DOMAINS]
    if bad:
        raise SystemExit(f"classical: unknown domain(s) {', '.join(bad)}; known: {', '.join(DOMAINS)}")
    if fd_driver() is None:
        raise SystemExit("classical: Fast Downward not found (pip install up-fast-downward)")
    wanted = set(_numbers(args.instances)) if args.instances else None
    root, prefix = None, "p"
    if args.scale:
        root = args.scale_dir or Path(tempfile.mkdtemp(prefix="nowplan-scale-"))
        write_instances(domains, root, scale=True)
        prefix = "s"
    tasks = [(d, p) for d in domains for p in (instance_files(d, root, prefix) if root else instance_files(d))
             if wanted is None or int(p.stem[1:]) in wanted]
    if not tasks:
        raise SystemExit("classical: no instance matches --domains/--instances")
    # nowplan runs from this checkout's sources: compile their bytecode once, as `pip install` does for an
    # installed package (the Fast Downward driver's is), else with PYTHONDONTWRITEBYTECODE set every
    # process compiles every module again (~0.1 s of its wall time)
    compileall.compile_dir(str(ROOT / "src" / "nowplan"), quiet=1)
    load0 = [round(x, 2) for x in os.getloadavg()]
    t0 = time.perf_counter()
    rows = run_all(tasks, args.time_limit, args.memory_limit or None, shlex.split(args.nowplan_args))
    meta = {
        "command": " ".join(["benchmarks/classical.py", *(argv if argv is not None else sys.argv[1:])]),
        "time_limit": args.time_limit, "memory_limit_mb": args.memory_limit, "commit": _commit(),
        "machine": f"{platform.machine()} {os.cpu_count()} cores, python {platform.python_version()}",
        "date": datetime.datetime.now().isoformat(timespec="seconds"),
        "load_before": load0, "load_after": [round(x, 2) for x in os.getloadavg()],
        "elapsed_s": round(time.perf_counter() - t0, 1), "planners": [OURS, FD],
    }
    args.out.mkdir(parents=True, exist_ok=True)
    write_csv(rows, csv_path)
    meta_path.write_text(json.dumps(meta, indent=2) + "\n")
    text = markdown(read_csv(csv_path), meta)
    md_path.write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
