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
"""

from __future__ import annotations

import heapq
import math
from typing import Literal

from nowplan.planning.task import Task

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
        self.task = task
        self.kind = kind
        self.acost = adapt_costs(task.cost, cost_type)
        self.npre = [len(p) for p in task.pre]
        self.nfacts = len(task.facts)
        self.goal = task.goal
        self.goalset = frozenset(task.goal)
        self.evaluations = 0

    def evaluate(self, state: frozenset[int]) -> tuple[float, list[int]]:
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
        for f in state:
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
        if self.kind == "add":
            return sum(cost[g] for g in self.goal), []
        if use_max:
            return max(cost[g] for g in self.goal), []
        chosen: set[int] = set()
        marked: set[int] = set()
        stack = [g for g in self.goal if g not in state]
        while stack:
            f = stack.pop()
            if f in marked:
                continue
            marked.add(f)
            a = sup[f]
            if a in chosen:
                continue
            chosen.add(a)
            stack.extend(p for p in pre[a] if p not in state and p not in marked)
        h = sum(acost[a] for a in chosen)
        preferred = sorted(a for a in chosen if all(p in state for p in pre[a]))
        return h, preferred
