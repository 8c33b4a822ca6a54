"""Anytime plan improvement on a time budget: LAMA's later iterations, then plan neighborhood graph search.

After the first (greedy) plan, weighted A* searches run with decreasing
weights (5, 3, 2, 1) and h_FF, pruning every node whose path already costs
as much as the best plan so far; each plan found lowers that bound.  They
get ``WASTAR_SHARE`` of the budget (if the search with weight 1 runs out of
states below the bound, the plan is optimal and the improvement ends); the
rest goes to plan neighborhood graph search (:mod:`nowplan.planning.pngs`) around the best plan, which short-cuts
the detours a greedy plan keeps (measured on the 65 instances of
``benchmarks/classical.py``: see docs/engine.md).  Plans only ever get
cheaper.  With the compiled kernel (:mod:`nowplan.planning.native`) each
weighted A* runs in C (``Kernel.bounded_wastar``) with the same result as
:func:`_bounded_wastar`, and so does the neighborhood search.
"""

from __future__ import annotations

import heapq
import itertools
import math
import time
from collections.abc import Callable

from nowplan.planning.axioms import rule_costs
from nowplan.planning.forward import _apply, _goal_reached, _Successors
from nowplan.planning.hff import CostType, RelaxedHeuristic
from nowplan.planning.pngs import improve_by_neighborhood
from nowplan.planning.postprocess import eliminate_actions
from nowplan.planning.task import Task

WEIGHTS = (5.0, 3.0, 2.0, 1.0)
WASTAR_SHARE = 0.25  # of the budget for the weighted A* searches; the rest for the neighborhood search


def _bounded_wastar(task: Task, h: RelaxedHeuristic, succ: _Successors, weight: float, bound: float,
                    stop: Callable[[], bool]) -> list[int] | None:
    """A plan (action ids) cheaper than ``bound``, or ``None``."""
    init = task.init
    h0, _ = h.evaluate(init)
    if h0 == math.inf:
        return None
    tick = itertools.count()
    best_g: dict[frozenset[int], float] = {init: 0.0}
    parent: dict[frozenset[int], tuple[frozenset[int], int] | None] = {init: None}
    frontier = [(weight * h0, h0, next(tick), init)]
    cost = task.cost
    while frontier:
        _, _, _, state = heapq.heappop(frontier)
        g = best_g[state]
        if _goal_reached(task, state):
            if g >= bound:
                continue
            plan: list[int] = []
            cur = parent[state]
            while cur is not None:
                plan.append(cur[1])
                cur = parent[cur[0]]
            plan.reverse()
            return plan
        if stop():
            return None
        for a in succ(state):
            ng = g + cost[a]
            if ng >= bound:
                continue
            nxt = _apply(task, state, a)
            if ng >= best_g.get(nxt, math.inf):
                continue
            best_g[nxt] = ng
            parent[nxt] = (state, a)
            hv, _ = h.evaluate(nxt)
            if hv == math.inf:
                continue
            heapq.heappush(frontier, (ng + weight * hv, hv, next(tick), nxt))
    return None


def improve(task: Task, plan: list[int], budget_s: float, cost_type: CostType = "plusone",
            out_of_time: Callable[[], bool] = lambda: False, wastar_share: float = WASTAR_SHARE) -> list[int]:
    """A plan no costlier than ``plan``, searching for at most ``budget_s`` CPU seconds.

    ``wastar_share``: the part of the budget for the weighted A* searches (1: no
    neighborhood search, unless they end early).
    """
    start = time.process_time()
    end = start + budget_s
    end_wastar = start + wastar_share * budget_s

    def stop() -> bool:
        return time.process_time() > end or out_of_time()

    def stop_wastar() -> bool:
        return time.process_time() > end_wastar or stop()

    h = RelaxedHeuristic(task, "ff", cost_type)
    succ = _Successors(task, h.native)
    best = plan
    exhausted = False  # weighted A* with w = 1 found no cheaper plan and was not stopped
    for w in WEIGHTS:
        if stop_wastar():
            break
        while True:
            bound = sum(task.cost[a] for a in best)
            if h.native is not None:
                found = h.native.bounded_wastar(task.init, rule_costs(task, task.cost), w, bound, stop_wastar)
            else:
                found = _bounded_wastar(task, h, succ, w, bound, stop_wastar)
            if found is None:
                exhausted = w == 1.0 and not stop_wastar()
                break
            best = eliminate_actions(task, found)
    if exhausted or stop():
        return best
    return improve_by_neighborhood(task, best, stop, h.native)
