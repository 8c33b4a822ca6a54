"""Relaxed-plan heuristics over an integer task: h_add, h_max and h_FF.

One forward exploration of the delete relaxation from a state, Knuth's
generalisation of Dijkstra's algorithm: an action fires once all its
preconditions are reached, at the sum (h_add) or maximum (h_max) of their
costs plus its own.  It stops as soon as every goal fact is settled.  h_FF
then extracts a relaxed plan by following each fact's best supporter back
from the goal (Hoffmann and Nebel's FF; FD's ``ff()`` evaluator) and sums
its actions' costs; the relaxed plan's actions applicable in the state are
the *preferred operators* (FF's helpful actions) the search expands first.

``cost_type`` transforms action costs as FD's ``adapt_costs`` does: ``one``
(unit costs, LAMA's first iteration), ``plusone`` (cost + 1: cost-aware
but never blind to zero-cost actions) or ``normal``.

Tie-breaking is part of the result: the exploration pops the lowest cost
and, among equal costs, the entry pushed last; the state's facts are pushed
in ascending id order (not in the frozenset's hash order, which depends on
how the set was built); a fact's supporter is the first action to give it
a strictly lower cost; h sums the costs in a fixed order.  The compiled
kernel (:mod:`nowplan.planning.native`) computes the same numbers in C and
is used when it is built; this Python code is the reference and fallback.
"""

from __future__ import annotations

import heapq
import math
from typing import TYPE_CHECKING, Literal

from nowplan.planning.axioms import kernel_axioms, relaxed_task, rule_costs
from nowplan.planning.native import kernel_class
from nowplan.planning.task import Task, pre_rows

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel

CostType = Literal["one", "plusone", "normal"]
Kind = Literal["ff", "add", "max"]


def adapt_costs(costs: list[float], cost_type: CostType) -> list[float]:
    if cost_type == "one":
        return [1.0] * len(costs)
    if cost_type == "plusone":
        return [c + 1.0 for c in costs]
    return list(costs)


class RelaxedHeuristic:
    """``evaluate(state) -> (h, preferred action ids)``; ``h`` is ``inf`` at a dead end."""

    def __init__(self, task: Task, kind: Kind = "ff", cost_type: CostType = "plusone") -> None:
        self.nactions = len(task.pre)
        relaxed = relaxed_task(task)  # the task's rules (axioms) as relaxed actions of cost 0
        self.task = relaxed
        self.kind = kind
        self.acost = rule_costs(task, adapt_costs(task.cost, cost_type))
        self.npre = [len(p) for p in relaxed.pre]
        self.nfacts = len(task.facts)
        self.goal = task.goal
        self.goalset = frozenset(task.goal)
        self.evaluations = 0
        cls = kernel_class()
        nactions, axioms = kernel_axioms(task)
        self.native: Kernel | None = None if cls is None else cls(
            self.nfacts, relaxed.pre, relaxed.add, relaxed.dele, self.acost, task.goal,
            pre_rows(relaxed), relaxed.no_pre, kind,
            nactions=nactions, axioms=axioms)

    def evaluate(self, state: frozenset[int]) -> tuple[float, list[int]]:
        if self.native is not None:
            self.evaluations += 1
            return self.native.evaluate(state)
        return self.evaluate_py(state)

    def evaluate_py(self, state: frozenset[int]) -> tuple[float, list[int]]:
        """The Python computation of :meth:`evaluate` (the reference for the kernel)."""
        self.evaluations += 1
        task = self.task
        pre, add, by_pre, acost = task.pre, task.add, task.by_pre, self.acost
        use_max = self.kind == "max"
        inf = math.inf
        cost = [inf] * self.nfacts
        sup = [-1] * self.nfacts
        unsat = self.npre[:]
        acc = [0.0] * len(pre)
        left = sum(1 for g in self.goal if g not in state)
        if left == 0:
            return 0.0, []
        goalset = self.goalset
        heap: list[tuple[float, int, int]] = []
        tick = 0
        for f in sorted(state):
            cost[f] = 0.0
            tick -= 1
            heap.append((0.0, tick, f))
        for a in task.no_pre:
            c = acost[a]
            for e in add[a]:
                if c < cost[e]:
                    cost[e] = c
                    sup[e] = a
                    tick -= 1
                    heap.append((c, tick, e))
        heapq.heapify(heap)
        pop, push = heapq.heappop, heapq.heappush
        while heap:
            c, _, f = pop(heap)
            if c > cost[f]:
                continue
            if f in goalset and f not in state:
                left -= 1
                if left == 0:
                    break
            for a in by_pre.get(f, ()):
                if use_max:
                    if c > acc[a]:
                        acc[a] = c
                else:
                    acc[a] += c
                unsat[a] -= 1
                if unsat[a] == 0:
                    nc = acc[a] + acost[a]
                    for e in add[a]:
                        if nc < cost[e]:
                            cost[e] = nc
                            sup[e] = a
                            tick -= 1
                            push(heap, (nc, tick, e))
        if left:
            return inf, []
        h = 0.0
        if self.kind == "add":
            for g in self.goal:  # left to right, as the kernel does (sum() compensates from 3.12)
                h += cost[g]
            return h, []
        if use_max:
            return max(cost[g] for g in self.goal), []
        chosen: list[int] = []  # in the order chosen
        is_chosen: set[int] = set()
        marked: set[int] = set()
        stack = [g for g in self.goal if g not in state]
        while stack:
            f = stack.pop()
            if f in marked:
                continue
            marked.add(f)
            a = sup[f]
            if a in is_chosen:
                continue
            is_chosen.add(a)
            chosen.append(a)
            stack.extend(p for p in pre[a] if p not in state and p not in marked)
        for a in chosen:
            h += acost[a]
        preferred = sorted(a for a in chosen if a < self.nactions and all(p in state for p in pre[a]))
        return h, preferred
