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
sum a subgoal's values without asking which of its facts hold.  Only for tasks whose
action costs are numbers (a cost read off the belief would need every action
costed per call) and when the kernel is built; :func:`kernel_hadd` says whether.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

from nowplan.core.levels import LevelMap
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


def _compiled(task: GroundTask, top: int) -> _Compiled | None:
    if not task.all_fixed:
        return None
    key = ("kernel hadd", top)
    hit = task.memo.get(key)
    cls = kernel_class()
    if cls is None:
        return None
    if isinstance(hit, _Compiled):
        return hit
    nf = len(task.table)
    pre = [[f for f, c, _ in p if c > top] for p in task.pre]  # kept at the top level
    rows: list[list[int]] = [[] for _ in range(nf)]
    for k, p in enumerate(pre):
        for f in p:
            rows[f].append(k)
    by_pre = rows
    no_pre = [k for k, p in enumerate(pre) if not p]
    cost = [float(c) for c in task.fixed_cost if c is not None]
    empty: list[list[int]] = [[] for _ in pre]
    kernel = cls(nf, pre, task.effects, empty, cost, [], by_pre, no_pre, "add")
    # every negative fact with its positive twin (-1: not in the table), so that each fact that
    # holds in a call's belief is a fact of the explored state and costs 0
    T = task.table
    negatives = tuple((f, T.by_key.get((a.predicate, a.args, True), -1))
                      for f, a in enumerate(T.atoms[:nf]) if a.value is False)
    hit = task.memo[key] = _Compiled(kernel, nf, negatives)
    return hit


def kernel_hadd(task: GroundTask, top: int) -> bool:
    """Can :class:`KernelHadd` serve this task (kernel built, every cost a number)?"""
    return _compiled(task, top) is not None


class KernelHadd:
    """h_add of fact ids from one compiled exploration of every ground action (see the module docstring)."""

    def __init__(self, task: GroundTask, levels: LevelMap, true_now: frozenset[int]) -> None:
        comp = task.memo.get(("kernel hadd", levels.top))  # made by kernel_hadd
        if not isinstance(comp, _Compiled):
            comp = _compiled(task, levels.top)
        if comp is None:
            raise ValueError("KernelHadd needs the compiled kernel and numeric action costs (see kernel_hadd)")
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
