"""Auto-HPN against flat planning on real IPC files (issue 18, target 2), each run a ``nowplan`` process.

For every domain/problem pair of the folders (the layout of ``benchmarks/ipc_check.py``:
``FOLDER/NAME/domain.pddl`` with problems ``FOLDER/NAME/*.pddl``) this runs, as subprocesses with a
time limit (killed ``--grace`` s after it):

* flat: ``nowplan plan D P --json --time-limit T --improve I`` (``--flat-improve``, default 0: the first
  plan, as the executive's planner calls make; ``nowplan plan``'s own default, 1, improves it after);
* for each ``--strategies`` entry S: ``nowplan run D P --criticality auto --strategy S --json
  --time-limit T --trace TMP`` (the CLI adds ``refine-flat`` to an automatic hierarchy itself).

It records the outcome (``solved``/``reached``, or the status, the budget or the first line of the
error: ``CRASH`` for a traceback, ``refused`` for exit 2, ``killed`` past the grace), the plan or
execution cost, the planner's CPU (``planning_cpu_s`` of either JSON document), the process's CPU
(the child's user+sys time from ``os.wait4``: parse, set-up, planning, acting) and wall time, and
checks every solved plan and every reached run's executed actions (the trace's successful
``observation`` events) with Unified Planning's validator where its reader takes the files, else the
repository's independent checker ``tests/pddl_sim.py`` (``benchmarks/ipc_check.validate``): every
action applicable in turn and the goal true at the end.  Writes ``runs.jsonl`` (one line per run)
and ``auto_ipc.md`` (a table per pair, the reached counts and the CPU ratios auto / flat) into
``--out``.

    PYTHONPATH=src .venv/bin/python benchmarks/auto_ipc.py /tmp/ipc8 [/tmp/ipc9 ...] --time-limit 60 \\
        --problems 8 --strategies hpn,hpn+flexible --out benchmarks/results/auto_ipc/NAME

``--summarize RUN_DIR [RUN_DIR_AFTER] [--larger 1]`` prints the CPU ratios of stored runs (all pairs
both solve, and those whose flat planner needs at least ``--larger`` s) and, for two runs, an A/B of
their executed actions and costs.
"""

from __future__ import annotations

import argparse
import compileall
import importlib.util
import json
import logging
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from benchmarks.ipc_check import pairs, simulate, validate  # noqa: E402

HAS_UP = importlib.util.find_spec("unified_planning") is not None

LOG = logging.getLogger("auto_ipc")
CLI = "import sys; from nowplan.cli import main; raise SystemExit(main(sys.argv[1:]))"


def child(cmd: list[str], limit: float, grace: float) -> tuple[int | None, str, str, float, float]:
    """Run ``cmd``; (exit status or None if killed, stdout, stderr, child CPU s, wall s)."""
    t0 = time.monotonic()
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        proc = subprocess.Popen(cmd, stdout=out, stderr=err, text=True)
        deadline = t0 + limit + grace
        status: int | None = None
        cpu = 0.0
        while True:
            pid, wstatus, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                status = os.waitstatus_to_exitcode(wstatus)
                cpu = usage.ru_utime + usage.ru_stime
                break
            if time.monotonic() > deadline:
                proc.kill()
                _, _, usage = os.wait4(proc.pid, 0)
                cpu = usage.ru_utime + usage.ru_stime
                break
            time.sleep(0.02)
        proc.returncode = -9 if status is None else status  # reaped here: keep Popen from waiting again
        out.seek(0)
        err.seek(0)
        return status, out.read(), err.read(), cpu, time.monotonic() - t0


def first_error(stderr: str) -> str:
    lines = [ln for ln in stderr.splitlines() if ln.strip() and not ln.startswith("WARNING")]
    return lines[-1][:200] if lines else ""


def classify(status: int | None, stdout: str, stderr: str, limit: float, grace: float) -> tuple[str, Any]:
    """('ok', parsed JSON) or (outcome, note) for a run that gave no JSON document."""
    if status is None:
        return "killed", f"killed {grace:.0f} s after the {limit:g} s limit"
    if "Traceback" in stderr:
        return "crash", "CRASH: " + first_error(stderr)
    if status == 2:
        return "refused", first_error(stderr)
    try:
        return "ok", json.loads(stdout)
    except json.JSONDecodeError:
        return "error", f"exit {status}: " + first_error(stderr)


def executed_actions(trace: Path) -> list[str]:
    done: list[str] = []
    if not trace.exists():
        return done
    for line in trace.read_text().splitlines():
        ev = json.loads(line)
        # an auxiliary operator (reaching a disjunctive goal) prints as "": no action of the domain
        if ev.get("event") == "observation" and ev.get("success") and ev["action"]:
            done.append(ev["action"])
    return done


def run_flat(dom: Path, prob: Path, limit: float, grace: float, improve: float) -> dict[str, Any]:
    cmd = [sys.executable, "-c", CLI, "plan", str(dom), str(prob), "--json", "--time-limit", str(limit),
           "--improve", f"{improve:g}"]
    status, out, err, cpu, wall = child(cmd, limit, grace)
    kind, doc = classify(status, out, err, limit, grace)
    row: dict[str, Any] = {"setting": "flat", "process_cpu_s": round(cpu, 3), "wall_s": round(wall, 3)}
    if kind != "ok":
        return {**row, "outcome": kind, "note": doc}
    solved = doc.get("status") == "solved"
    row.update(outcome="solved" if solved else str(doc.get("status")), cost=doc.get("cost"),
               planning_cpu_s=doc.get("planning_cpu_s"), actions=len(doc.get("plan") or []),
               note="" if solved else str(doc.get("reason", ""))[:200], plan=list(doc.get("plan") or []))
    if solved:
        row["validation"] = validate(dom, prob, list(doc["plan"]), HAS_UP)
    return row


def setting_of(strategy: str) -> str:
    """A run's setting name in the rows and tables: the strategy (``run flat`` for the executive's flat
    strategy, apart from flat planning's ``flat``)."""
    return "run flat" if strategy == "flat" else strategy


def run_auto(dom: Path, prob: Path, strategy: str, limit: float, grace: float) -> dict[str, Any]:
    with tempfile.TemporaryDirectory(prefix="auto-ipc-") as tmp:
        trace = Path(tmp) / "trace.jsonl"
        cmd = [sys.executable, "-c", CLI, "run", str(dom), str(prob), "--criticality", "auto", "--strategy",
               strategy, "--json", "--time-limit", str(limit), "--trace", str(trace)]
        status, out, err, cpu, wall = child(cmd, limit, grace)
        kind, doc = classify(status, out, err, limit, grace)
        done = executed_actions(trace)
    row: dict[str, Any] = {"setting": setting_of(strategy), "process_cpu_s": round(cpu, 3), "wall_s": round(wall, 3),
                           "flat_fallback": "planning flat" in err}
    if kind != "ok":
        return {**row, "outcome": kind, "note": doc, "actions": len(done)}
    row.update(outcome=str(doc.get("outcome")), cost=doc.get("execution_cost"), planning_cpu_s=doc.get("planning_cpu_s"),
               actions=doc.get("actions"), plans_made=doc.get("plans_made"), note=str(doc.get("reason", ""))[:200],
               executed=done)  # for an A/B of two trees: the same executed actions
    if row["outcome"] == "reached":
        row["validation"] = validate(dom, prob, done, HAS_UP)
    return row


def ratio(a: Any, b: Any) -> str:
    return f"{a / b:.2f}" if isinstance(a, (int, float)) and isinstance(b, (int, float)) and b > 0 else ""


def cell(r: dict[str, Any]) -> str:
    ok = r["outcome"] in ("solved", "reached")
    cost = f" {r['cost']:g}" if ok and r.get("cost") is not None else ""
    bad = "" if not ok or str(r.get("validation", "")).startswith("valid") else f" **{r.get('validation')}**"
    return f"{r['outcome']}{cost}{bad}"


def tables(rows: list[dict[str, Any]], strategies: list[str], header: str) -> str:
    by: dict[str, dict[str, dict[str, Any]]] = {}
    for r in rows:
        by.setdefault(r["pair"], {})[r["setting"]] = r
    head = "| pair | flat | flat plan CPU s | flat proc CPU s |" + "".join(
        f" {s} | plan CPU s | proc CPU s | plan CPU / flat | proc CPU / flat |" for s in strategies) + " notes |"
    lines = [header, "", head, "|" + "---|" * (4 + 5 * len(strategies) + 1)]
    counts = {s: [0, 0, 0] for s in strategies}  # reached, reached where flat solved, valid
    flat_solved = 0
    for pair, rs in by.items():
        f = rs.get("flat", {"outcome": "-"})
        flat_ok = f["outcome"] == "solved"
        flat_solved += flat_ok
        line = f"| {pair} | {cell(f)} | {f.get('planning_cpu_s', '')} | {f.get('process_cpu_s', '')} |"
        notes = [f"flat: {f['note']}"] if f.get("note") else []
        for s in strategies:
            a = rs.get(s, {"outcome": "-"})
            ok = a["outcome"] == "reached"
            counts[s][0] += ok
            counts[s][1] += ok and flat_ok
            counts[s][2] += ok and str(a.get("validation", "")).startswith("valid")
            both = ok and flat_ok
            line += (f" {cell(a)} | {a.get('planning_cpu_s', '')} | {a.get('process_cpu_s', '')} |"
                     f" {ratio(a.get('planning_cpu_s'), f.get('planning_cpu_s')) if both else ''} |"
                     f" {ratio(a.get('process_cpu_s'), f.get('process_cpu_s')) if both else ''} |")
            if a.get("note"):
                notes.append(f"{s}: {a['note']}")
            if a.get("flat_fallback"):
                notes.append(f"{s}: hierarchy not used (dead end), planned flat")
        lines.append(line + " " + "; ".join(notes).replace("|", "/")[:400] + " |")
    summary = [f"{len(by)} pairs; flat solved {flat_solved}"]
    for s, (n, where, valid) in counts.items():
        summary.append(f"{s}: reached {n} ({where} where flat solved), executed actions valid {valid}")
    return "\n".join([*lines[:1], "", "; ".join(summary), *lines[1:], ""])


def load_runs(path: Path) -> dict[tuple[str, str], dict[str, Any]]:
    return {(r["pair"], r["setting"]): r for r in map(json.loads, path.read_text().splitlines())}


def summarize(dirs: list[Path], strategy: str, larger: float) -> str:
    """The CPU ratios auto / flat of each stored run (``runs.jsonl``) over the pairs both solve, those
    whose flat planner took at least ``larger`` s apart; with two runs (before, after) also an A/B of
    the runs both trees reached: the same executed actions (where stored) and costs."""
    out: list[str] = []
    runs = [load_runs(d / "runs.jsonl") for d in dirs]
    for d, rs in zip(dirs, runs):
        both = [(f, a) for (pair, s), a in rs.items() if s == strategy and a["outcome"] == "reached"
                and (f := rs.get((pair, "flat"), {})).get("outcome") == "solved"]
        out.append(f"{d}: {len(both)} pairs both solve")
        for what in ("planning_cpu_s", "process_cpu_s"):
            r = sorted(a[what] / f[what] for f, a in both if f.get(what) and a.get(what) is not None)
            if r:
                out.append(f"  {what}: below flat on {sum(x < 1 for x in r)} of {len(r)}, median "
                           f"{statistics.median(r):.2f}, worst {r[-1]:.2f}")
        big = sorted((f["pair"], a["process_cpu_s"] / f["process_cpu_s"], a.get("planning_cpu_s", 0) / f["planning_cpu_s"])
                     for f, a in both if (f.get("planning_cpu_s") or 0) >= larger)
        out.append(f"  flat planner >= {larger:g} s: {len(big)} pairs, process CPU below flat on "
                   f"{sum(p < 1 for _, p, _ in big)}: " + ", ".join(f"{n} {p:.2f} (plan {q:.2f})" for n, p, q in big))
    if len(runs) == 2:
        a, b = runs
        same = diff = 0
        notes: list[str] = []
        for key, ra in a.items():
            rb = b.get(key)
            if rb is None or ra["outcome"] not in ("solved", "reached") or rb["outcome"] != ra["outcome"]:
                if rb is not None and ra["outcome"] != rb["outcome"]:
                    notes.append(f"{key[0]} {key[1]}: {ra['outcome']} -> {rb['outcome']}")
                continue
            steps = "executed" if key[1] != "flat" else "plan"
            if ra.get("cost") == rb.get("cost") and ra.get(steps, []) == rb.get(steps, []):
                same += 1
            else:
                diff += 1
                notes.append(f"{key[0]} {key[1]}: cost {ra.get('cost')} -> {rb.get('cost')}")
        out.append(f"A/B {dirs[0]} -> {dirs[1]}: {same} runs solved/reached in both with the same actions and "
                   f"cost, {diff} different" + "".join(f"\n  {n}" for n in notes))
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    if argv is None:
        argv = sys.argv[1:]
    if argv and argv[0] == "--summarize":  # --summarize RUN_DIR [RUN_DIR_AFTER] [--larger S]
        sp = argparse.ArgumentParser(prog="auto_ipc.py --summarize")
        sp.add_argument("dirs", type=Path, nargs="+")
        sp.add_argument("--strategy", default="hpn")
        sp.add_argument("--larger", type=float, default=1.0, help="the larger pairs: flat planner CPU >= this")
        sa = sp.parse_args(argv[1:])
        print(summarize(sa.dirs, sa.strategy, sa.larger))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folders", type=Path, nargs="+")
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--grace", type=float, default=20.0, help="kill a run this long after its time limit")
    ap.add_argument("--problems", type=int, default=8, help="problems per domain folder (name order)")
    ap.add_argument("--strategies", default="hpn,hpn+flexible")
    ap.add_argument("--flat-improve", type=float, default=0.0,
                    help="flat planning's --improve (default 0: its first plan, as the executive's planner calls)")
    ap.add_argument("--only", default="", help="comma-separated substrings of the pair names to run")
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    src = ROOT / "src" / "nowplan"
    compileall.compile_dir(str(src), quiet=1)  # as benchmarks/ipc_check.py: no recompiling in every child
    strategies = [s for s in args.strategies.split(",") if s]
    only = [s for s in args.only.split(",") if s]
    args.out.mkdir(parents=True, exist_ok=True)
    rows: list[dict[str, Any]] = []
    load0 = os.getloadavg()
    with open(args.out / "runs.jsonl", "w") as jl:
        for folder in args.folders:
            for name, dom, prob in pairs(folder, args.problems):
                pair = f"{folder.name}/{name}"
                if only and not any(o in pair for o in only):
                    continue
                for r in [run_flat(dom, prob, args.time_limit, args.grace, args.flat_improve),
                          *(run_auto(dom, prob, s, args.time_limit, args.grace) for s in strategies)]:
                    r = {"pair": pair, **r}
                    rows.append(r)
                    jl.write(json.dumps(r) + "\n")
                    jl.flush()
                    LOG.info("%s %s: %s (proc CPU %.2f s) %s", pair, r["setting"], cell(r), r["process_cpu_s"],
                             r.get("note", ""))
    header = (f"# auto-HPN vs flat on real IPC files ({', '.join(str(f) for f in args.folders)})\n\n"
              f"`benchmarks/auto_ipc.py --time-limit {args.time_limit:g} --problems {args.problems} --strategies "
              f"{args.strategies} --flat-improve {args.flat_improve:g}`, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load average "
              f"{load0[0]:.1f} at the start and {os.getloadavg()[0]:.1f} at the end (2 shared cores: compare CPU "
              "figures within one run only). 'plan CPU' is the planner's CPU as the run reports it; 'proc CPU' the "
              "whole process's (parse to exit). Validation: Unified Planning's validator, else tests/pddl_sim.py, "
              "replays the plan or the executed actions on the original files (a failed check is shown in bold).")
    (args.out / "auto_ipc.md").write_text(tables(rows, [setting_of(s) for s in strategies], header))
    LOG.info("wrote %s", args.out / "auto_ipc.md")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
