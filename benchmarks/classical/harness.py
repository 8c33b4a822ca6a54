"""Run ``nowplan plan`` and Fast Downward on a PDDL problem, and check the plans.

* :func:`run_nowplan` runs ``python -m nowplan.cli plan DOMAIN PROBLEM --json``
  as a subprocess (the CLI's default engine, whatever it is) and reads its
  JSON; :func:`solve_in_process` calls the same command in this process.
* :func:`run_fd` runs Fast Downward's driver from the ``up_fast_downward``
  package (``--alias lama-first`` by default) and reads its plan file and its
  ``Expanded N state(s)`` and ``Evaluated N state(s)`` lines.  Compare
  nowplan's lazy searches (gbfs, lama) with FD's *Evaluated* count: nowplan's
  ``expanded`` counts every new state taken out of the open lists, dead ends
  (h = inf) included, which is FD's lazy search's evaluated count; FD's
  *Expanded* leaves the dead ends out (IPC-2006 trucks p07, lama-first: 5,041
  expanded, 24,572 evaluated, 19,530 dead ends; benchmarks/results/trucks_hff).
* :func:`check_plan` replays a plan in nowplan's core model (every
  precondition, then the goal) and returns its cost.

Wall times include the process start.  A process still running at the
time limit is killed with its whole process group (FD's translator and
search run as children of its driver).
"""

from __future__ import annotations

import contextlib
import io
import json
import logging
import math
import os
import re
import resource
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

log = logging.getLogger(__name__)

ROOT = Path(__file__).resolve().parents[2]
SRC = ROOT / "src"
_EXPANDED = re.compile(r"Expanded (\d+) state\(s\)\.")
_EVALUATED = re.compile(r"Evaluated (\d+) state\(s\)\.")
_PLANNER_TIME = re.compile(r"Planner time: ([0-9.]+)s")
_ACTION = re.compile(r"^\(\s*([^\s()]+)((?:\s+[^\s()]+)*)\s*\)$")


@dataclass
class Run:
    """One planner on one problem."""

    planner: str
    solved: bool
    status: str
    wall_s: float
    plan: list[str] = field(default_factory=list)
    cost: float | None = None  # as the planner reports it
    expansions: int | None = None
    method: str = ""
    planning_s: float | None = None  # the planner's own time, without process start, if it reports one
    cpu_s: float | None = None  # user + system CPU of the process and the children it waited for
    evaluated: int | None = None  # FD only: states evaluated (its lazy search's new states, dead ends included)


def fd_driver() -> Path | None:
    """``fast-downward.py`` inside the installed ``up_fast_downward`` package, or None."""
    try:
        import up_fast_downward
    except ImportError:
        return None
    path = Path(up_fast_downward.__file__).parent / "downward" / "fast-downward.py"
    return path if path.is_file() else None


def _limit_memory(mb: int | None) -> Callable[[], None] | None:
    if mb is None:
        return None

    def set_limit() -> None:  # in the child, before exec
        resource.setrlimit(resource.RLIMIT_AS, (mb * 2**20, mb * 2**20))

    return set_limit


def _children_cpu() -> float:
    ru = resource.getrusage(resource.RUSAGE_CHILDREN)
    return ru.ru_utime + ru.ru_stime


_last_cpu: list[float] = [0.0]  # CPU seconds of the last process _timed ran (reaped children's rusage delta)


def _timed(cmd: Sequence[str], limit: float, *, cwd: Path | None = None, env: dict[str, str] | None = None,
           memory_mb: int | None = None) -> tuple[int | None, str, str, float]:
    """``(exit code or None if killed at the limit, stdout, stderr, wall seconds)``.

    The process's CPU time (its own and that of the children it waited for, as
    ``getrusage(RUSAGE_CHILDREN)`` counts them) is left in ``_last_cpu[0]``.
    """
    c0 = _children_cpu()
    t0 = time.perf_counter()
    proc = subprocess.Popen(list(cmd), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=cwd,
                            env=env, start_new_session=True, preexec_fn=_limit_memory(memory_mb))
    try:
        out, err = proc.communicate(timeout=limit)
        code: int | None = proc.returncode
    except subprocess.TimeoutExpired:
        with contextlib.suppress(ProcessLookupError):
            os.killpg(proc.pid, signal.SIGKILL)  # the group this call started: driver and children
        out, err = proc.communicate()
        code = None
    wall = time.perf_counter() - t0
    _last_cpu[0] = round(_children_cpu() - c0, 4)
    return code, out, err, wall


def _env() -> dict[str, str]:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(SRC), *filter(None, [env.get("PYTHONPATH")])])
    return env


def run_nowplan(domain: Path, problem: Path, time_limit: float, *, extra: Sequence[str] = (),
                memory_mb: int | None = None) -> Run:
    """``nowplan plan DOMAIN PROBLEM --json --time-limit T`` as a subprocess, killed after T seconds."""
    cmd = [sys.executable, "-m", "nowplan.cli", "plan", str(domain), str(problem), "--json",
           "--time-limit", f"{time_limit:g}", *extra]
    code, out, err, wall = _timed(cmd, time_limit, env=_env(), memory_mb=memory_mb)
    cpu = _last_cpu[0]
    if code is None:
        return Run("nowplan", False, "time_limit (killed)", wall, cpu_s=cpu)
    try:
        doc: dict[str, Any] = json.loads(out)
    except json.JSONDecodeError:
        last = (err.strip().splitlines() or ["no output"])[-1]
        return Run("nowplan", False, f"error (exit {code}): {last[:200]}", wall, cpu_s=cpu)
    plan = [str(a) for a in doc.get("plan") or []]
    solved = doc.get("status") == "solved"
    cost, took = doc.get("cost"), doc.get("planning_time_s")
    return Run("nowplan", solved, str(doc.get("status", "")), wall, plan,
               float(cost) if cost is not None else None, doc.get("expanded"),
               str(doc.get("method") or doc.get("engine") or ""), float(took) if took is not None else None,
               cpu)


def read_fd_plan(path: Path) -> tuple[list[str], float | None]:
    """Actions and the ``; cost = N`` comment of a Fast Downward plan file."""
    if not path.is_file():
        return [], None
    actions, cost = [], None
    for line in path.read_text().splitlines():
        line = line.strip()
        if line.startswith("("):
            actions.append(line)
        m = re.match(r";\s*cost\s*=\s*([0-9.]+)", line)
        if m:
            cost = float(m.group(1))
    return actions, cost


def fd_expansions(stdout: str) -> int | None:
    """The last ``Expanded N state(s).`` count of a Fast Downward log (not the 'until last jump' one)."""
    found = _EXPANDED.findall(stdout)
    return int(found[-1]) if found else None


def fd_evaluated(stdout: str) -> int | None:
    """The last ``Evaluated N state(s).`` count of a Fast Downward log: like nowplan's lazy ``expanded``."""
    found = _EVALUATED.findall(stdout)
    return int(found[-1]) if found else None


def run_fd(domain: Path, problem: Path, time_limit: float, *, alias: str = "lama-first",
           memory_mb: int | None = None) -> Run:
    """Fast Downward ``--alias ALIAS`` in a temporary directory, killed after ``time_limit`` seconds."""
    exe = fd_driver()
    name = f"fd-{alias}"
    if exe is None:
        return Run(name, False, "missing (pip install up-fast-downward)", 0.0)
    with tempfile.TemporaryDirectory(prefix="nowplan-fd-") as tmp:
        plan_file = Path(tmp) / "sas_plan"
        cmd = [sys.executable, str(exe), "--overall-time-limit", f"{math.ceil(time_limit)}s"]
        if memory_mb is not None:
            cmd += ["--overall-memory-limit", f"{memory_mb}M"]
        cmd += ["--plan-file", str(plan_file), "--alias", alias, str(domain.resolve()), str(problem.resolve())]
        code, out, _err, wall = _timed(cmd, time_limit, cwd=Path(tmp))
        cpu = _last_cpu[0]
        actions, cost = read_fd_plan(plan_file)
    expansions, evaluated = fd_expansions(out), fd_evaluated(out)
    took = _PLANNER_TIME.findall(out)
    planning_s = float(took[-1]) if took else None
    if code is None:
        return Run(name, False, "time_limit (killed)", wall, expansions=expansions, method=alias, cpu_s=cpu,
                   evaluated=evaluated)
    if not actions and code != 0:
        status = {11: "unsolvable", 12: "unsolved (incomplete search)", 22: "memory_limit", 23: "time_limit",
                  24: "time_limit"}.get(code, f"no plan (exit {code})")
        return Run(name, False, status, wall, expansions=expansions, method=alias, cpu_s=cpu, evaluated=evaluated)
    return Run(name, True, "solved", wall, actions, cost if cost is not None else float(len(actions)),
               expansions, alias, planning_s, cpu, evaluated)


def parse_action(text: str) -> tuple[str, list[str]]:
    """``"(move a b)"`` → ``("move", ["a", "b"])``."""
    m = _ACTION.match(text.strip())
    if m is None:
        raise ValueError(f"not a PDDL action: {text!r}")
    return m.group(1), m.group(2).split()


def check_plan(domain: Path, problem: Path, actions: Sequence[str]) -> tuple[bool, str, float | None]:
    """``(valid, message, cost)``: replay ``actions`` in nowplan's core model from the initial state.

    Every precondition must hold before its action, and the goal at the end;
    the cost is the sum of the actions' costs (the domain's constant costs,
    1 each without ``:action-costs``).
    """
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.fd import ground_actions

    prob = load_pddl(domain, problem, mutexes=False)
    dom = prob.domain
    try:
        ground = ground_actions(prob, [parse_action(a) for a in actions])
    except Exception as exc:  # a ModelError or a malformed line: the plan does not fit the problem
        return False, f"the plan does not fit the problem: {exc}", None
    state = prob.init
    cost = 0.0
    for i, a in enumerate(ground, start=1):
        missing = [str(p) for p in a.preconditions() if not dom.holds(p, state)]
        if missing:
            return False, f"step {i} {a.pddl()}: precondition(s) {', '.join(missing)} do not hold", None
        cost += a.cost(state)
        state = state.apply(a.effects())
    unmet = [str(g) for g in prob.goal.atoms if not dom.holds(g, state)]
    if unmet:
        return False, f"the goal is not reached: {', '.join(sorted(unmet))}", None
    return True, f"valid plan of {len(ground)} action(s)", cost


def solve_in_process(domain: Path, problem: Path, time_limit: float = 30.0) -> tuple[dict[str, Any], float]:
    """``nowplan plan DOMAIN PROBLEM --json`` in this process: (its JSON document, process CPU seconds)."""
    from nowplan.cli import build_parser

    args = build_parser().parse_args(["plan", str(domain), str(problem), "--json",
                                      "--time-limit", f"{time_limit:g}"])
    buf = io.StringIO()
    c0 = time.process_time()
    with contextlib.redirect_stdout(buf):
        args.func(args)
    cpu = time.process_time() - c0
    doc: dict[str, Any] = json.loads(buf.getvalue())
    return doc, cpu
