"""Ground h_add of every fact in one compiled exploration per planner call.

The regression search asks h_add for its subgoals' facts.  In Python,
:class:`~nowplan.planning.hadd_relevant.RelevantHadd` explores only the backward
closure of the facts asked for and keeps the values across calls; in the domains
where it matters (logistics: every vehicle's move touches every package's closure)
most of that is explored again after each action.  With the compiled kernel
(:mod:`nowplan.planning.native`) one exploration of *every* ground action takes
tens of microseconds, so :class:`KernelHadd` runs it once per call
(``Kernel.costs``) and answers each fact with a list lookup.

The values are those of :func:`nowplan.planning.heuristics.hadd_ids` (tested in
``tests/test_hadd_relevant.py``): the kernel holds the task's preconditions kept
at the call's top level; actions the level map puts at another level are passed
with their own preconditions; a negative precondition whose atom is false is a
fact of the explored state (free), as in ``hadd_ids``; so is every other negative
fact that holds, which gives each fact that holds the value 0 and lets the search
sum a subgoal's values without asking which of its facts hold.  When the kernel is built
(:func:`kernel_hadd` says whether); a task whose costs read the belief has every action
costed in the call, and a kernel is compiled per distinct vector of costs (the latest
``VARIABLE_KEPT`` are kept: the calls from one state, or from states where no cost changed,
share one).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.ground_task import GroundTask
from nowplan.planning.native import kernel_class

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel


class _Compiled:
    """A task's kernel at one top level, and its negative preconditions (fact, positive twin)."""

    def __init__(self, kernel: Kernel, nfacts: int, negatives: tuple[tuple[int, int], ...]) -> None:
        self.kernel = kernel
        self.nfacts = nfacts
        kernel.set_base([f for f, _ in negatives])  # every negation holds, but for those of true facts
        self.negative_of = {t: f for f, t in negatives if t >= 0}  # positive fact -> its negation

    def costs(self, true_now: frozenset[int], over: list[tuple[int, list[int]]]) -> list[float]:
        """Every fact's value from the facts that hold: the true ones and the negations of the others."""
        neg, n = self.negative_of, self.nfacts
        off = [neg[f] for f in true_now if f in neg]
        true: Iterable[int] = true_now if all(f < n for f in true_now) else [f for f in true_now if f < n]
        return self.kernel.costs(true, over, off)


VARIABLE_KEPT = 4  # kernels kept per task and top level for costs that read the belief


def _compiled(task: GroundTask, top: int, costs: list[float] | None = None) -> _Compiled | None:
    """The task's kernel at ``top``; ``costs``: every action's cost in this call (a task whose costs
    read the belief; ``None`` there: no kernel)."""
    if not task.all_fixed and costs is None:
        return None
    cls = kernel_class()
    if cls is None:
        return None
    if task.all_fixed:
        key: tuple[object, ...] = ("kernel hadd", top)
    else:
        assert costs is not None
        key = ("kernel hadd", top, tuple(costs))
    hit = task.memo.get(key)
    if isinstance(hit, _Compiled):
        return hit
    nf = len(task.table)
    pre = task.pre_at(top)  # kept at the top level
    rows: list[list[int]] = [[] for _ in range(nf)]
    for k, p in enumerate(pre):
        for f in p:
            rows[f].append(k)
    by_pre = rows
    no_pre = [k for k, p in enumerate(pre) if not p]
    cost = [float(c) for c in task.fixed_cost if c is not None] if costs is None else costs
    empty: list[list[int]] = [[] for _ in pre]
    kernel = cls(nf, pre, task.effects, empty, cost, [], by_pre, no_pre, "add")
    # every negative fact with its positive twin (-1: not in the table), so that each fact that
    # holds in a call's belief is a fact of the explored state and costs 0
    T = task.table
    negatives = tuple((f, T.by_key.get((a.predicate, a.args, True), -1))
                      for f, a in enumerate(T.atoms[:nf]) if a.value is False)
    hit = task.memo[key] = _Compiled(kernel, nf, negatives)
    if costs is not None:  # keep the latest few of the belief-dependent ones
        kept = task.memo.setdefault(("kernel hadd variable", top), [])
        assert isinstance(kept, list)
        kept.append(key)
        while len(kept) > VARIABLE_KEPT:
            task.memo.pop(kept.pop(0), None)
    return hit


def kernel_hadd(task: GroundTask, top: int, variable_costs: bool = False) -> bool:
    """Can :class:`KernelHadd` serve this task (the kernel built; every cost a number, or
    ``variable_costs``: the caller costs every action per call)?"""
    if not task.all_fixed:
        return variable_costs and kernel_class() is not None
    return _compiled(task, top) is not None


class CostsUnavailable(Exception):
    """An action's cost could not be had for every action at once (the search asks costs lazily instead)."""


class KernelHadd:
    """h_add of fact ids from one compiled exploration of every ground action (see the module docstring)."""

    def __init__(self, task: GroundTask, levels: LevelMap, true_now: frozenset[int],
                 cost: Callable[[Action], float] | None = None) -> None:
        costs = None
        if not task.all_fixed:  # costs that read the belief: every action's, in this call
            if cost is None:
                raise ValueError("KernelHadd: this task's costs read the belief; pass cost")
            fixed = task.fixed_cost
            try:
                costs = [cost(task.action(k)) if fixed[k] is None else float(fixed[k] or 0.0) for k in range(task.n)]
            except Exception as e:  # (e.g. a PDDL cost the :init leaves undefined for an unreachable instance)
                raise CostsUnavailable(str(e)) from e
        comp = _compiled(task, levels.top, costs)
        if comp is None:
            raise ValueError("KernelHadd needs the compiled kernel (see kernel_hadd)")
        self.task = task
        over: list[tuple[int, list[int]]] = []
        for k, lv in task.lowered(levels).items():
            over.append((k, [f for f, c, _ in task.pre[k] if c > lv]))
        self.values = comp.costs(true_now, over)  # 0 for every fact below nfacts that holds
        self.nfacts = comp.nfacts

    def get(self, f: int) -> float:
        """h_add of fact ``f`` (``inf`` when the relaxation does not reach it)."""
        return self.values[f] if f < self.nfacts else math.inf

    def extend(self, facts: Iterable[int]) -> None:
        """Every fact is valued already (the interface of RelevantHadd)."""
