"""Reuse-enforced replanning: plan under the previous plan's structure (seed 004 VI-A, Alg. 2).

:func:`skeleton` abstracts the unexecuted tail of the last plan: operator
names and *constant* arguments (objects, grasps, drawers) are kept, every
non-constant (a pose, configuration, trajectory or hypothetical value —
anything whose ``constant`` attribute is False) becomes a free variable
``@k``; the same old value gives the same free variable.

:func:`constrained_plan` is Alg. 2's compiled problem solved directly: the
plan must be exactly the skeleton's actions in order (``Applied i``), each
constant fixed, each free variable bound once and then reused
(``Bound``/``Assigned``).  It regresses the goal backwards through the
skeleton, grounding each step through the domain's generators, with
backtracking, until the current belief satisfies the pre-image — or the
time budget runs out.  A step whose arguments are all constants (and whose
operator binds nothing by generators) is the one instance it names, so a
ground skeleton (a flat plan of symbolic steps) is regressed step by step
without grounding achievers.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Action, Operator
from nowplan.planning.context import PlanningContext
from nowplan.planning.grounding import Grounder
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.preimage import achieves
from nowplan.planning.regression import preimage

log = logging.getLogger(__name__)


@dataclass(frozen=True, order=True)
class FreeVar:
    """A free variable ``@k`` of a skeleton."""

    k: int

    def __str__(self) -> str:
        return f"@{self.k}"


@dataclass(frozen=True)
class SkeletonStep:
    name: str
    args: tuple[Any, ...]  # constants, or FreeVar

    def __str__(self) -> str:
        return f"{self.name}({', '.join(str(a) for a in self.args)})"


def is_constant(value: Any) -> bool:
    return bool(getattr(value, "constant", True))


def skeleton(actions: Sequence[Action]) -> tuple[SkeletonStep, ...]:
    """Constants kept, non-constants replaced by free variables (one per distinct value)."""
    names: dict[Any, FreeVar] = {}
    out = []
    for act in actions:
        args = []
        for a in act.args:
            if is_constant(a):
                args.append(a)
            else:
                args.append(names.setdefault(a, FreeVar(len(names))))
        out.append(SkeletonStep(act.name, tuple(args)))
    return tuple(out)


def _match(step: SkeletonStep, act: Action, fv: Mapping[FreeVar, Any]) -> dict[FreeVar, Any] | None:
    if act.name != step.name or len(act.args) != len(step.args):
        return None
    new = dict(fv)
    for want, got in zip(step.args, act.args, strict=True):
        if isinstance(want, FreeVar):
            if want in new and new[want] != got:
                return None  # (Bound v) -> (Assigned v ?p)
            new[want] = got
        elif want != got:
            return None  # a constant keeps its value
    return new


def constrained_plan(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    skel: Sequence[SkeletonStep],
    time_budget: float,
    context: PlanningContext | None = None,
    max_generator_values: int = 8,
    max_nodes: int = 5_000,
    clock: Callable[[], float] = time.perf_counter,
) -> PlanResult:
    """A plan following ``skel`` exactly (fresh values for its free variables), or a failure;
    ``time_budget`` is measured on ``clock`` (wall time unless told)."""
    cpu0 = time.process_time()
    deadline = clock() + time_budget
    grounder = Grounder(domain, objects, belief, context, max_generator_values)
    operators = {op.name: op for op in domain.operators}
    levels = flat_levels()
    expanded = 0
    holds_cache: dict[Any, bool] = {}

    def satisfied(g: Goal) -> bool:
        for a in g.atoms:
            r = holds_cache.get(a)
            if r is None:
                r = domain.holds(a, belief)
                holds_cache[a] = r
            if not r:
                return False
        return True

    class _Stop(Exception):
        pass

    def search(g: Goal, k: int, fv: dict[FreeVar, Any]) -> Iterator[list[tuple[Action, Goal]]]:
        nonlocal expanded
        if k == 0:
            if satisfied(g):
                yield []
            return
        expanded += 1
        if expanded > max_nodes or clock() > deadline:
            raise _Stop
        step = skel[k - 1]
        fixed = _fixed_action(step, operators)
        if fixed is not None:  # every argument a constant: the one instance there is (no achievers to ground)
            if achieves(g, fixed, domain):
                pre = preimage(g, fixed, None, domain)
                if pre is not None:
                    for rest in search(pre, k - 1, fv):
                        yield [*rest, (fixed, g)]
                        return
            return
        tried: set[tuple[str, tuple[Any, ...]]] = set()
        for target in sorted(g.atoms):
            for act in grounder.achievers(target, g):
                if act.key in tried:
                    continue
                tried.add(act.key)
                nfv = _match(step, act, fv)
                if nfv is None:
                    continue
                pre = preimage(g, act, None, domain)
                if pre is None:
                    continue
                for rest in search(pre, k - 1, nfv):
                    yield [*rest, (act, g)]
                    return

    status, reason, steps = PlanStatus.UNSOLVABLE, "no instance of the previous plan's skeleton", None
    try:
        for found in search(goal, len(skel), {}):
            steps = found
            break
    except _Stop:
        status = PlanStatus.TIME_LIMIT
        reason = f"constrained planning budget of {time_budget:g} s or {max_nodes} nodes spent"
    cpu = time.process_time() - cpu0
    if steps is None:
        return PlanResult(status, None, reason, expanded=expanded, cpu_time_s=cpu, method="constrained")
    first = goal if not steps else _start_goal(steps, domain)
    plan_steps = (PlanStep(None, first), *(PlanStep(a, g) for a, g in steps))
    return PlanResult(
        PlanStatus.SOLVED, Plan(plan_steps, levels), "", expanded=expanded, cpu_time_s=cpu,
        method="constrained",
    )


def _fixed_action(step: SkeletonStep, operators: Mapping[str, Operator]) -> Action | None:
    """The action a skeleton step names when every argument is a constant and its operator binds
    nothing by generators (else ``None``: the step is matched against the grounder's achievers).
    On a long ground skeleton (a flat plan of ~100 steps in the held-out mill shop) grounding every
    achiever of every goal atom at each step made a constrained replan slower than a fresh plan."""
    op = operators.get(step.name)
    if op is None or op.generators or len(op.params) != len(step.args):
        return None
    if any(isinstance(a, FreeVar) for a in step.args):
        return None
    return op.instantiate(dict(zip(op.params, step.args, strict=True)))


def _start_goal(steps: list[tuple[Action, Goal]], domain: Domain) -> Goal:
    pre = preimage(steps[0][1], steps[0][0], None, domain)
    assert pre is not None
    return pre
