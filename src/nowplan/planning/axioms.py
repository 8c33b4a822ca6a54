"""Derived facts of a ground task: stratified fixpoint evaluation, and the relaxation with axioms.

A task with axioms (the ground rules of recursive derived predicates,
:mod:`nowplan.io.pddl_axioms`) keeps its derived facts in every state, as
Fast Downward's search does: after an action's effects, every derived fact
(and the "not d" fact of a derived atom used negatively) is cleared and the
rules are evaluated stratum by stratum, each to its least fixpoint, by
counting the unmet conditions of each rule (a rule fires once all its
conditions hold; each fact and rule is handled at most once per
evaluation).  After a stratum, ``not d`` is set for each of its derived atoms
``d`` that did not become true: higher strata may use it.

For the heuristics the rules are relaxed operators of cost 0 (FD's
treatment of axioms in the delete relaxation), and every ``not d`` of a
derived atom is reachable at cost 0 (an over-approximation of negated
derived facts: the relaxation stays a relaxation, so h_max stays admissible
and a dead end found by h is a real one).  :func:`relaxed_task` gives that
task; its actions beyond ``len(task.actions)`` are the rules, never applied
in the search nor returned as preferred operators.

The compiled kernel (:mod:`nowplan.planning.native`) evaluates the rules
with the same algorithm; this Python code is the reference.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from nowplan.planning.task import GroundAxioms, Task


class AxiomEvaluator:
    """``evaluate(facts) -> state``: the base facts of ``facts`` closed under the rules."""

    def __init__(self, ax: GroundAxioms) -> None:
        self.ax = ax
        self.nbody = [len(b) for b in ax.body]
        self.by_body: dict[int, list[int]] = {}
        for r, body in enumerate(ax.body):
            for f in body:
                self.by_body.setdefault(f, []).append(r)

    def evaluate(self, facts: Iterable[int]) -> frozenset[int]:
        ax = self.ax
        derived, head, by_body = ax.derived, ax.head, self.by_body
        true = {f for f in facts if f not in derived}
        unsat = self.nbody[:]
        for f in true:
            for r in by_body.get(f, ()):
                unsat[r] -= 1
        for (lo, hi), negs in zip(ax.layers, ax.negs, strict=True):
            queue = [head[r] for r in range(lo, hi) if unsat[r] == 0]
            while queue:
                h = queue.pop()
                if h in true:
                    continue
                true.add(h)
                for r in by_body.get(h, ()):
                    unsat[r] -= 1
                    if unsat[r] == 0 and lo <= r < hi:
                        queue.append(head[r])
            for d, nd in negs:
                if d not in true and nd not in true:
                    true.add(nd)
                    for r in by_body.get(nd, ()):
                        unsat[r] -= 1
        return frozenset(true)


def evaluator(task: Task) -> AxiomEvaluator | None:
    """The task's evaluator (made once), or ``None`` without axioms."""
    if not task.axioms:
        return None
    ev = task.memo.get("axioms")
    if ev is None:
        ev = task.memo["axioms"] = AxiomEvaluator(task.axioms)
    assert isinstance(ev, AxiomEvaluator)
    return ev


def relaxed_task(task: Task) -> Task:
    """The task whose extra actions (ids from ``len(task.actions)``) are the rules, cost 0.

    One more action adds every "not d" fact of a derived atom (no
    conditions, cost 0).  Without axioms: ``task`` itself.
    """
    if not task.axioms:
        return task
    hit = task.memo.get("relaxed")
    if isinstance(hit, Task):
        return hit
    ax = task.axioms
    nots = tuple(sorted(nd for negs in ax.negs for _, nd in negs))
    pre = [*task.pre, *ax.body, ()]
    add = [*task.add, *((h,) for h in ax.head), nots]
    dele = [*task.dele, *(() for _ in ax.head), ()]
    cost = [*task.cost, *(0.0 for _ in ax.head), 0.0]
    out = Task(task.facts, task.index, task.actions, pre, add, dele, cost, task.init, task.goal,
               task.unsolvable)
    out.index_preconditions()
    task.memo["relaxed"] = out
    return out


def rule_costs(task: Task, costs: list[float]) -> list[float]:
    """Action costs (already adapted) followed by 0 for each rule of the relaxed task."""
    return [*costs, *[0.0] * (len(relaxed_task(task).pre) - len(task.pre))]


AxiomArgs = tuple[Sequence[Sequence[int]], Sequence[int], Sequence[tuple[int, int]], Sequence[Sequence[int]],
                  Sequence[int]]


def kernel_axioms(task: Task) -> tuple[int, AxiomArgs | None]:
    """The compiled kernel's ``nactions`` and ``axioms`` arguments for ``task`` (``None``: no axioms)."""
    ax = task.axioms
    if not ax:
        return len(task.pre), None
    return len(task.pre), (ax.body, ax.head, ax.layers, [[f for pair in negs for f in pair] for negs in ax.negs],
                           sorted(ax.derived))
