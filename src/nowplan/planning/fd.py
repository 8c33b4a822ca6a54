"""A flat engine: Fast Downward through unified-planning (extra ``fd``).

:func:`solve_fd` exports a problem at an abstraction level to PDDL in a
temporary directory (:func:`nowplan.io.pddl_write.export_level`), reads it
with UPF's PDDL reader and runs ``OneshotPlanner(name="fast-downward")``.
The action list it returns is turned into a nowplan :class:`Plan` by
regressing the goal backwards through it (:func:`plan_from_actions`), so the
pre-images are exactly those the regression planner would compute and the
executive can monitor them.
"""

from __future__ import annotations

import logging
import tempfile
import time
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action
from nowplan.errors import ModelError, require
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.preimage import regress_through, static_drop

log = logging.getLogger(__name__)


def _levels(level: int | None) -> LevelMap:
    return flat_levels() if level is None else LevelMap(level)


def ground_actions(problem: Problem, steps: Iterable[tuple[str, Sequence[str]]]) -> list[Action]:
    """``[(name, args)]`` as ground actions of ``problem.domain`` (names case-insensitive)."""
    ops = {o.name.lower(): o for o in problem.domain.operators}
    ops.update({o.name.lower().replace("-", "_"): o for o in problem.domain.operators})
    known = {o.lower(): o for o in problem.all_objects}
    out: list[Action] = []
    for name, args in steps:
        op = ops.get(name.lower())
        if op is None:
            raise ModelError(f"the plan uses the unknown action '{name}'")
        if len(args) != len(op.params):
            raise ModelError(f"action {name} takes {len(op.params)} argument(s), got {len(args)}")
        vals = []
        for a in args:
            if a.lower() not in known:
                raise ModelError(f"the plan uses the unknown object '{a}' in action {name}")
            vals.append(known[a.lower()])
        out.append(op.instantiate(dict(zip(op.params, vals, strict=True))))
    return out


def plan_from_actions(
    problem: Problem, actions: Sequence[Action], levels: LevelMap, goal: Goal | None = None
) -> Plan:
    """The plan ``[(None, g0), (a1, g1), ..., (an, goal)]`` with regressed pre-images.

    Raises :class:`ModelError` if an action destroys the goal it is meant to
    serve or if the initial state does not satisfy ``g0`` (the action list
    is not a plan at this level).
    """
    domain = problem.domain
    goal = goal if goal is not None else problem.goal
    belief = problem.init
    goals, failed = regress_through(goal, actions, levels, domain, static_drop(domain, belief))
    if failed is not None:
        raise ModelError(f"step {failed + 1} ({actions[failed].pddl()}) destroys an atom its successors need")
    missing = [str(x) for x in goals[0].atoms if not domain.holds(x, belief)]
    if missing:
        raise ModelError("the initial state does not satisfy the plan's pre-image: " + ", ".join(missing))
    steps = [PlanStep(None, goals[0])] + [
        PlanStep(a, g) for a, g in zip(actions, goals[1:], strict=True)
    ]
    return Plan(tuple(steps), levels)


def _status(up_status: Any) -> PlanStatus | None:
    name = getattr(up_status, "name", str(up_status))
    if name.startswith("SOLVED"):
        return PlanStatus.SOLVED
    if name.startswith("UNSOLVABLE"):
        return PlanStatus.UNSOLVABLE
    if name == "TIMEOUT":
        return PlanStatus.TIME_LIMIT
    return None


def solve_fd(
    problem: Problem,
    level: int | None = None,
    *,
    time_limit: float = 60.0,
    keep_dir: str | Path | None = None,
) -> PlanResult:
    """Solve ``problem`` at ``level`` (None: flat, every precondition) with Fast Downward."""
    if problem.domain.axioms:
        from nowplan.errors import UsageError

        raise UsageError(f"--engine fd: domain {problem.domain.name} has recursive derived predicates, so "
                         f"derived predicates evaluated by rules ({', '.join(sorted(problem.domain.derived))}), which unified-planning's PDDL reader "
                         "(the way to Fast Downward here) does not read; use the default engine, or run Fast "
                         "Downward's own driver on the original files (benchmarks/ipc_check.py does)")
    require("unified_planning", "fd")
    require("up_fast_downward", "fd")
    shortcuts = require("unified_planning.shortcuts", "fd")
    from unified_planning.io import PDDLReader

    from nowplan.io.pddl_write import write_pddl

    shortcuts.get_environment().credits_stream = None
    shortcuts.get_environment().error_used_name = False  # PDDL lets an action and a predicate share a name
    t_cpu, t0 = time.process_time(), time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="nowplan-fd-") as tmp:
        out = Path(keep_dir) if keep_dir is not None else Path(tmp)
        dom_path, prob_path = write_pddl(problem, out, level)
        up_problem = PDDLReader().parse_problem(str(dom_path), str(prob_path))
        # the reader cannot be interrupted: its time counts against the limit, and the planner gets the rest
        left = time_limit - (time.perf_counter() - t0)
        if left <= 0:
            return PlanResult(PlanStatus.TIME_LIMIT, None,
                              f"time limit of {time_limit:g} s reached while unified-planning read the problem",
                              cpu_time_s=time.process_time() - t_cpu, method="fast-downward")
        with shortcuts.OneshotPlanner(name="fast-downward") as planner:
            res = planner.solve(up_problem, timeout=left)
    wall = time.perf_counter() - t0
    status = _status(res.status)
    common: dict[str, Any] = {"cpu_time_s": time.process_time() - t_cpu, "method": "fast-downward"}
    if status is None:
        return PlanResult(PlanStatus.UNSOLVABLE, None,
                          f"fast-downward ended with status {res.status.name}", **common)
    if status is not PlanStatus.SOLVED or res.plan is None:
        reason = {
            PlanStatus.UNSOLVABLE: "fast-downward: no plan exists at this level",
            PlanStatus.TIME_LIMIT: f"time limit of {time_limit:g} s reached",
        }.get(status, res.status.name)
        return PlanResult(status, None, reason, **common)
    pairs = [
        (a.action.name, [str(p) for p in a.actual_parameters]) for a in res.plan.actions
    ]
    actions = ground_actions(problem, pairs)
    plan = plan_from_actions(problem, actions, _levels(level))
    log.info("fast-downward: plan of %d steps in %.2f s", len(plan), wall)
    return PlanResult(PlanStatus.SOLVED, plan, "", **common)
