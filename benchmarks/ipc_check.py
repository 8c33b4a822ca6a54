"""Run ``nowplan plan`` (and Fast Downward, where installed) on a folder of PDDL domain/problem pairs.

Issue 18's target: every classical IPC file that Fast Downward's translator
accepts, ``nowplan plan`` accepts.  This script takes a folder laid out as

* ``FOLDER/NAME/domain.pddl`` with problems ``FOLDER/NAME/*.pddl`` (the first
  ``--problems`` of them in name order; a per-instance domain ``FOLDER/NAME/p01-domain.pddl``
  is used for ``p01.pddl`` when it exists, as in Fast Downward's benchmark layout), or
* ``FOLDER/NAME-domain.pddl`` with ``FOLDER/NAME-p01.pddl`` (tests/data/pddl_ipc_style),

and for each pair runs ``nowplan plan D P --json --time-limit T`` and Fast
Downward's own driver (``fast-downward.py --alias lama-first``, the copy that
the up_fast_downward package ships; skipped without it) on the ORIGINAL files,
so its translator decides what it accepts; each as a subprocess killed after
T + 30 s.  It validates nowplan's plan with the
Unified Planning validator where its reader takes the files (else with the
repository's independent checker, tests/pddl_sim.py), and writes a Markdown
table (accepted? solved? cost, FD's cost, validation, the first line of any
error) to ``--out`` (default: stdout).  An error exit (2) is a refusal by
the front end; a traceback is reported as a crash.

    PYTHONPATH=src .venv/bin/python benchmarks/ipc_check.py /tmp/ipc --time-limit 30 \
        --out benchmarks/results/ipc_check.md
"""

from __future__ import annotations

import argparse
import compileall
import importlib.util
import json
import re
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

CLI = "import sys; from nowplan.cli import main; raise SystemExit(main(sys.argv[1:]))"


@dataclass
class Outcome:
    accepted: bool
    solved: bool
    cost: float | None
    plan: list[str]
    note: str
    wall: float


def pairs(folder: Path, problems: int) -> list[tuple[str, Path, Path]]:
    out: list[tuple[str, Path, Path]] = []
    for d in sorted(p for p in folder.iterdir() if p.is_dir()):
        # one domain.pddl for the folder, or a domain per instance (FD's benchmark layout: p01-domain.pddl)
        probs = sorted(p for p in d.glob("*.pddl") if "domain" not in p.name)
        for p in probs[:problems]:
            dom = d / f"{p.stem}-domain.pddl"
            if not dom.exists():
                dom = d / "domain.pddl"
            if dom.exists():
                out.append((d.name if problems == 1 else f"{d.name}/{p.stem}", dom, p))
    for dom in sorted(folder.glob("*-domain.pddl")):
        name = dom.name[: -len("-domain.pddl")]
        prob = folder / f"{name}-p01.pddl"
        if prob.exists():
            out.append((name, dom, prob))
    return out


def run(dom: Path, prob: Path, limit: float, extra: list[str]) -> Outcome:
    cmd = [sys.executable, "-c", CLI, "plan", str(dom), str(prob), "--json", "--time-limit", str(limit), *extra]
    t0 = time.monotonic()
    try:
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=limit + 30)
    except subprocess.TimeoutExpired:
        return Outcome(True, False, None, [], f"killed after {limit + 30:.0f} s", time.monotonic() - t0)
    wall = time.monotonic() - t0
    err = [ln for ln in proc.stderr.splitlines() if ln.strip() and not ln.startswith("WARNING")]
    if "Traceback" in proc.stderr:
        return Outcome(False, False, None, [], "CRASH: " + (err[-1] if err else "")[:160], wall)
    if proc.returncode == 2:
        return Outcome(False, False, None, [], "refused: " + (err[-1] if err else "")[:200], wall)
    try:
        doc = json.loads(proc.stdout)
    except json.JSONDecodeError:
        return Outcome(False, False, None, [], f"exit {proc.returncode}: " + (err[-1] if err else "")[:160], wall)
    solved = doc.get("status") == "solved"
    return Outcome(True, solved, doc.get("cost") if solved else None, list(doc.get("plan") or []),
                   "" if solved else f"{doc.get('status')}: {str(doc.get('reason', ''))[:120]}", wall)


def fd_driver() -> Path | None:
    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or spec.origin is None:
        return None
    driver = Path(spec.origin).parent / "downward" / "fast-downward.py"
    return driver if driver.exists() else None


def run_fd(driver: Path, dom: Path, prob: Path, limit: float) -> Outcome:
    """Fast Downward (lama-first) on the original files; 'accepted' = its translator did not fail."""
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="ipc-fd-") as tmp:
        cmd = [sys.executable, str(driver), "--alias", "lama-first", "--search-time-limit", f"{limit:g}",
               str(dom.resolve()), str(prob.resolve())]
        try:
            proc = subprocess.run(cmd, capture_output=True, text=True, timeout=limit + 30, cwd=tmp)
        except subprocess.TimeoutExpired:
            return Outcome(True, False, None, [], f"killed after {limit + 30:.0f} s", time.monotonic() - t0)
        plan_file = Path(tmp) / "sas_plan"
        text = plan_file.read_text() if plan_file.exists() else ""
    wall = time.monotonic() - t0
    if "translate exit code: 0" not in proc.stdout:
        out_lines = proc.stdout.split("translate exit code")[0].splitlines()
        lines = [ln.strip() for ln in out_lines if ln.strip() and not ln.startswith(("INFO", "["))]
        return Outcome(False, False, None, [], "FD translator failed: " + " ".join(lines[-2:])[:120], wall)
    if not text:
        return Outcome(True, False, None, [], f"FD: no plan (exit {proc.returncode})", wall)
    m = re.search(r"; cost = ([0-9.]+)", text)
    plan = [ln.strip() for ln in text.splitlines() if ln.startswith("(")]
    return Outcome(True, True, float(m.group(1)) if m else float(len(plan)), plan, "", wall)


SIM = Path(__file__).resolve().parent.parent / "tests" / "pddl_sim.py"


def simulate(dom: Path, prob: Path, plan: list[str]) -> str:
    """The repository's independent checker (tests/pddl_sim.py: its own reader and ADL semantics)."""
    spec = importlib.util.spec_from_file_location("pddl_sim", SIM)
    if spec is None or spec.loader is None:
        return "no checker"
    sim = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(sim)
    try:
        sim.check_plan(dom.read_text(errors="replace"), prob.read_text(errors="replace"), plan)
    except AssertionError as exc:
        return f"INVALID (sim): {str(exc)[:80]}"
    except Exception as exc:  # the checker's reader is small: say so, do not guess
        return f"sim cannot read ({type(exc).__name__})"
    return "valid (sim)"


def validate(dom: Path, prob: Path, plan: list[str], has_up: bool) -> str:
    """Unified Planning's validator where its reader takes the files, else tests/pddl_sim.py."""
    if has_up:
        try:
            from nowplan.planning.validate import validate_plan

            ok, msg = validate_plan(dom, prob, plan)
        except Exception:  # UP's own reader refuses some lenient inputs: not our verdict
            pass
        else:
            return "valid (UP)" if ok else f"INVALID (UP): {msg[:80]}"
    return simulate(dom, prob, plan) if SIM.exists() else "not validated"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", type=Path)
    ap.add_argument("--time-limit", type=float, default=30.0)
    ap.add_argument("--problems", type=int, default=1, help="problems per domain folder (name order)")
    ap.add_argument("--no-fd", action="store_true")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--plan-args", default="", metavar="ARGS",
                    help="extra options for every `nowplan plan` run, e.g. '--cost-type one'")
    args = ap.parse_args(argv)
    # nowplan runs from this checkout's sources: compile their bytecode once, as `pip install` does (and as
    # benchmarks/classical.py does; the Fast Downward driver's is installed compiled), else with
    # PYTHONDONTWRITEBYTECODE set every run compiles every module again (~0.3 s of a small problem's wall time)
    src = Path(__file__).resolve().parent.parent / "src" / "nowplan"
    if src.is_dir():
        compileall.compile_dir(str(src), quiet=1)
    driver = None if args.no_fd else fd_driver()
    has_fd = driver is not None
    has_up = importlib.util.find_spec("unified_planning") is not None
    rows = ["| domain | problem | accepted | solved | cost | FD accepted | FD solved | FD cost | validation "
            "| time s | FD time s | time / FD | note |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    n = acc = sol = fd_acc = fd_sol = both = acc_where_fd = valid = 0
    ratios: list[float] = []
    for name, dom, prob in pairs(args.folder, args.problems):
        n += 1
        ours = run(dom, prob, args.time_limit, args.plan_args.split())
        fd = run_fd(driver, dom, prob, args.time_limit) if driver is not None else None
        acc += ours.accepted
        sol += ours.solved
        fd_sol += bool(fd and fd.solved)
        fd_acc += bool(fd and fd.accepted)
        acc_where_fd += bool(fd and fd.accepted and ours.accepted)
        both += bool(ours.solved and fd and fd.solved)
        check = validate(dom, prob, ours.plan, has_up) if ours.solved else "-"
        valid += check.startswith("valid")
        if ours.solved and fd is not None and fd.solved and fd.wall > 0:
            ratios.append(ours.wall / fd.wall)
        fd_cells = ("-", "-", "-", "-") if fd is None else (
            "yes" if fd.accepted else "no", "yes" if fd.solved else "no",
            "" if fd.cost is None else f"{fd.cost:g}", f"{fd.wall:.1f}")
        note = ours.note or (f"FD: {fd.note}" if fd and fd.note else "")
        ratio = f"{ours.wall / fd.wall:.2f}" if ours.solved and fd is not None and fd.solved and fd.wall > 0 else ""
        rows.append(f"| {name} | {prob.name} | {'yes' if ours.accepted else 'no'} | {'yes' if ours.solved else 'no'} "
                    f"| {'' if ours.cost is None else f'{ours.cost:g}'} | {fd_cells[0]} | {fd_cells[1]} | {fd_cells[2]} "
                    f"| {check} | {ours.wall:.1f} | {fd_cells[3]} | {ratio} | {note.replace('|', '/')} |")
        print(rows[-1], file=sys.stderr, flush=True)
    ratios.sort()
    spread = (f"; wall time / FD's where both solved: median {ratios[len(ratios) // 2]:.2f}, worst {ratios[-1]:.2f}"
              if ratios else "")
    summary = (f"{n} pairs: accepted {acc}, solved {sol}, plans valid {valid}"
               + (f"; Fast Downward (original files) accepted {fd_acc}, solved {fd_sol}; nowplan accepted "
                  f"{acc_where_fd} of the {fd_acc} FD accepts; both solved {both}{spread}"
                  if has_fd else "; Fast Downward not installed"))
    text = "\n".join([summary, "", *rows, ""])
    if args.out:
        args.out.write_text(text)
    print(summary)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
