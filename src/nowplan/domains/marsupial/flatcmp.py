"""Flat planners against HPN and RCHPN on marsupial instances (seed 002 V-B).

Each instance is exported with :func:`.flat.flatten` and
:func:`nowplan.io.pddl_write.write_pddl`, then solved under a time limit by
Fast Downward (``lama-first``; an optimal configuration, ``seq-opt-lmcut``,
on small instances) and pyperplan (greedy best-first with h_FF), run as
subprocesses of their own drivers; every plan they return is checked with
unified-planning's validator (:func:`nowplan.planning.validate.validate_plan`).
Our HPN and RCHPN solve the hierarchical instance in the simulated world;
their time is the CPU time of the whole run (all planning and optimizing).
Every planner gets the same limit in CPU seconds (FD's own limit is one;
pyperplan gets an RLIMIT_CPU; a run of ours that ends after it counts as a
time-out), so a loaded machine does not favour anyone.  Flat plan costs are
rescored with our cost model (:func:`.flat.rescore`).
"""

from __future__ import annotations

import importlib.util
import logging
import math
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from nowplan.core.domain import Problem
from nowplan.domains.marsupial.flat import flatten, rescore
from nowplan.domains.marsupial.problems import MapSpec

log = logging.getLogger(__name__)
# limits are CPU seconds (Fast Downward's --overall-time-limit is one too); wall-clock allowance for a
# shared, loaded machine: this many times the CPU limit
WALL_SLACK = 10.0


def _downward() -> Path | None:
    try:
        import up_fast_downward
    except ImportError:
        return None
    path = Path(up_fast_downward.__file__).parent / "downward" / "fast-downward.py"
    return path if path.is_file() else None


def _child_cpu() -> float:
    """CPU seconds of every finished child process (and their own children, e.g. FD's translator)."""
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


def _read_plan(path: Path) -> list[str]:
    if not path.is_file():
        return []
    return [ln.strip() for ln in path.read_text().splitlines() if ln.strip().startswith("(")]


def run_fd(dom: Path, prob: Path, alias: str, limit: float, work: Path) -> dict[str, Any]:
    exe = _downward()
    if exe is None:
        return {"status": "missing (pip install 'nowplan[fd]')"}
    plan = work / f"sas_plan_{alias}"
    t0, c0 = time.perf_counter(), _child_cpu()
    proc = subprocess.run(
        [sys.executable, str(exe), "--overall-time-limit", f"{int(limit)}s", "--plan-file", str(plan),
         "--alias", alias, str(dom), str(prob)],
        capture_output=True, text=True, cwd=work, check=False,
    )
    wall, cpu = time.perf_counter() - t0, _child_cpu() - c0
    steps = _read_plan(plan)
    if not steps:
        timed_out = "time limit" in proc.stdout.lower() or proc.returncode in (23, 24)
        status = "time_limit" if timed_out else f"no plan (exit {proc.returncode})"
        return {"status": status, "time_s": cpu, "wall_s": wall}
    return {"status": "solved", "time_s": cpu, "wall_s": wall, "steps": steps}


def without_costs(dom: Path, prob: Path, work: Path) -> tuple[Path, Path]:
    """Copies without action costs (pyperplan reads plain STRIPS only)."""
    d = re.sub(r"\s*\(increase \(total-cost\) [0-9.]+\)", "", dom.read_text())
    d = d.replace(" :action-costs", "").replace("  (:functions (total-cost) - number)\n", "")
    q = prob.read_text().replace("(= (total-cost) 0)", "")
    q = re.sub(r"\s*\(:metric minimize \(total-cost\)\)", "", q)
    out_d, out_q = work / "domain-nocost.pddl", work / "problem-nocost.pddl"
    out_d.write_text(d)
    out_q.write_text(q)
    return out_d, out_q


def _cpu_limit(limit: float) -> Callable[[], None]:
    def set_limit() -> None:  # in the child, before exec: killed by SIGXCPU after `limit` CPU seconds
        n = max(1, math.ceil(limit))
        resource.setrlimit(resource.RLIMIT_CPU, (n, n + 1))

    return set_limit


def run_pyperplan(dom: Path, prob: Path, limit: float) -> dict[str, Any]:
    """pyperplan (greedy best-first, h_FF) on a cost-free copy, limited to ``limit`` CPU seconds."""
    if importlib.util.find_spec("pyperplan") is None:
        return {"status": "missing (pip install pyperplan)"}
    dom, prob = without_costs(dom, prob, dom.parent)
    t0, c0 = time.perf_counter(), _child_cpu()
    try:
        proc = subprocess.run(
            [sys.executable, "-m", "pyperplan", "-H", "hff", "-s", "gbf", str(dom), str(prob)],
            capture_output=True, timeout=limit * WALL_SLACK, check=False, preexec_fn=_cpu_limit(limit))
    except subprocess.TimeoutExpired:
        return {"status": "time_limit (wall)", "time_s": _child_cpu() - c0, "wall_s": time.perf_counter() - t0}
    wall, cpu = time.perf_counter() - t0, _child_cpu() - c0
    soln = Path(str(prob) + ".soln")
    steps = _read_plan(soln)
    if soln.exists():
        soln.unlink()
    if not steps:
        if proc.returncode in (-signal.SIGXCPU, -signal.SIGKILL) or cpu >= 0.95 * limit:
            status = "time_limit"
        else:  # e.g. 1 after a MemoryError
            status = f"no plan (exit {proc.returncode})"
        return {"status": status, "time_s": cpu, "wall_s": wall}
    return {"status": "solved", "time_s": cpu, "wall_s": wall, "steps": steps}


def timed_run(ep: Any, strategy: str, seed: int, limit: float) -> tuple[Any, float, bool]:
    """Run an episode under ``strategy`` with the marsupial planner settings: (metrics, CPU s, goal holds).

    ``limit`` is in CPU seconds; the executive's own (wall-clock) budget is ``WALL_SLACK`` times it,
    so that a loaded machine does not change the results.
    """
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.marsupial.model import PLANNER

    st = parse_strategy(strategy, max_actions=20_000, max_plans=50_000, time_limit=limit * WALL_SLACK,
                        planner=PLANNER)
    c0 = time.process_time()
    m = run_episode(ep, st, seed=seed)
    cpu = time.process_time() - c0
    return m, cpu, bool(ep.problem.domain.satisfies(ep.world.state, ep.problem.goal))


def run_ours(problem: Problem, spec: MapSpec, strategy: str, seed: int, limit: float) -> dict[str, Any]:
    """Solve the hierarchical instance in the simulated world; time = CPU of the whole run.

    Like the flat planners, ours get ``limit`` CPU seconds: the executive's own (wall-clock) budget is
    ``WALL_SLACK`` times that, and a run that reaches the goal after ``limit`` CPU seconds counts as
    a time-out (its cost is kept as ``late_cost``).
    """
    from nowplan.domains.marsupial.scenarios import make_episode

    m, cpu, ok = timed_run(make_episode(problem, spec, seed), strategy, seed, limit)
    out: dict[str, Any] = {"status": "solved" if ok else m.outcome.value, "time_s": cpu,
                           "planning_cpu_s": m.planning_cpu_s, "cost": m.execution_cost if ok else None,
                           "steps": m.actions}
    if ok and cpu > limit:
        out.update(status="time_limit", cost=None, late_cost=m.execution_cost)
    return out


def compare(
    name: str, problem: Problem, spec: MapSpec, limit: float, optimal: bool, seed: int = 0
) -> list[dict[str, Any]]:
    """One row per planner for one instance (FD and pyperplan plans validated with unified-planning)."""
    from nowplan.io.pddl_write import write_pddl
    from nowplan.planning.validate import validate_plan

    n = sum(1 for t in problem.objects.values() if t == "package")
    rows: list[dict[str, Any]] = []
    with tempfile.TemporaryDirectory(prefix="nowplan-marsupial-") as tmp:
        work = Path(tmp)
        dom, prob = write_pddl(flatten(problem), work)
        flat_runs = {"fd lama-first": run_fd(dom, prob, "lama-first", limit, work)}
        if optimal:
            flat_runs["fd seq-opt-lmcut"] = run_fd(dom, prob, "seq-opt-lmcut", limit, work)
        flat_runs["pyperplan gbf hff"] = run_pyperplan(dom, prob, limit)
        for planner, r in flat_runs.items():
            row: dict[str, Any] = {"instance": name, "packages": n, "planner": planner, "status": r["status"],
                                   "time_s": round(r.get("time_s", math.nan), 2)}
            if r.get("steps"):
                ok, msg = validate_plan(dom, prob, r["steps"])
                row.update(cost=rescore(r["steps"]), pddl_cost=pddl_cost(r["steps"]), valid=ok,
                           steps=len(r["steps"]))
                if not ok:
                    log.warning("%s plan for %s does not validate: %s", planner, name, msg)
                    row["status"] = "invalid plan"
            rows.append(row)
    for strategy in ("hpn", "hpn+peephole"):
        r = run_ours(problem, spec, strategy, seed, limit)
        rows.append({"instance": name, "packages": n, "planner": strategy, "status": r["status"],
                     "time_s": round(r["time_s"], 2), "cost": r["cost"], "steps": r["steps"],
                     **({"late_cost": r["late_cost"]} if "late_cost" in r else {})})
    opt = next((r.get("cost") for r in rows if r["planner"] == "fd seq-opt-lmcut" and r.get("valid")), None)
    if opt:
        for r in rows:
            if r.get("cost") is not None:
                r["cost_over_optimum"] = round(r["cost"] / opt, 3)
    return rows


def pddl_cost(actions: Sequence[str]) -> float:
    """Cost of a flat plan in the flat PDDL metric (every loader step costs 1)."""
    big = ("load", "unload", "travel")
    return sum(10.0 if a.strip("()").split()[0].split("-")[0] in big else 1.0 for a in actions)


def instances(regimes: Sequence[str], sizes: Sequence[int], seeds: Sequence[int]) -> list[tuple[str, Problem, MapSpec]]:
    """The FF instance, then one generated instance per regime, size and seed."""
    from nowplan.domains.marsupial.problems import ff_instance, generate

    out: list[tuple[str, Problem, MapSpec]] = [("ff", *ff_instance(0))]
    for regime in regimes:
        for n in sizes:
            for s in seeds:
                p, spec = generate(regime, n, s)
                out.append((p.name, p, spec))
    return out


def run_table(
    regimes: Sequence[str], sizes: Sequence[int], seeds: Sequence[int], limit: float, optimal_upto: int
) -> list[dict[str, Any]]:
    """Every planner on every instance (an optimal FD run where the instance has <= optimal_upto packages)."""
    from nowplan.experiments import progress

    rows: list[dict[str, Any]] = []
    bar = progress.bar(None, "marsupial flat comparison", unit="instance")  # drawn before generating
    todo = instances(regimes, sizes, seeds)
    bar.reset(total=len(todo))
    for name, problem, spec in todo:
        n = sum(1 for t in problem.objects.values() if t == "package")
        log.info("flat comparison: %s", name)
        bar.set_postfix_str(name, refresh=False)
        rows += compare(name, problem, spec, limit, optimal=n <= optimal_upto)
        bar.update(1)
    bar.close()
    return rows


def speedups(rows: Sequence[dict[str, Any]], ours: str, theirs: str = "fd lama-first") -> list[dict[str, Any]]:
    """Per instance: their time / our time (a lower bound when they hit the limit), both statuses."""
    out = []
    for name in dict.fromkeys(r["instance"] for r in rows):
        a = next((r for r in rows if r["instance"] == name and r["planner"] == ours), None)
        b = next((r for r in rows if r["instance"] == name and r["planner"] == theirs), None)
        if a is None or b is None or a["status"] != "solved" or not a["time_s"]:
            continue
        out.append({"instance": name, "packages": a["packages"], "ours": ours, "ours_s": a["time_s"],
                    "theirs": theirs, "theirs_s": b["time_s"], "theirs_status": b["status"],
                    "ratio": round(b["time_s"] / a["time_s"], 1),
                    "bound": "lower bound" if b["status"] != "solved" else "exact"})
    return out


def markdown(rows: Sequence[dict[str, Any]]) -> str:
    """The table of runs as Markdown."""
    head = ("| instance | packages | planner | status | CPU s | cost (ours) | cost (PDDL) | steps | cost / optimum "
            "| cost if late |")
    lines = [head, "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append("| " + " | ".join(str(r.get(k, "")) if r.get(k) is not None else "" for k in (
            "instance", "packages", "planner", "status", "time_s", "cost", "pddl_cost", "steps",
            "cost_over_optimum", "late_cost")) + " |")
    return "\n".join(lines) + "\n"
