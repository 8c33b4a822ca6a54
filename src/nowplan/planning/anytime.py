"""Anytime plan improvement on a work budget: LAMA's later iterations, then plan neighborhood graph search.

After the first (greedy) plan, weighted A* searches run with decreasing
weights (5, 3, 2, 1) and h_FF, pruning every node whose path already costs
as much as the best plan so far; each plan found lowers that bound.  They
get ``WASTAR_SHARE`` of the budget (if the search with weight 1 runs out of
states below the bound, the plan is optimal and the improvement ends); the
rest goes to plan neighborhood graph search (:mod:`nowplan.planning.pngs`) around the best plan, which short-cuts
the detours a greedy plan keeps (measured on the 65 instances of
``benchmarks/classical.py``: see docs/engine.md).  Plans only ever get
cheaper.

The budget counts work, not seconds, so the plan found depends neither on the
machine's load nor on the kernel being compiled.  Its unit is about one h_FF
evaluation: a weighted A* expansion costs ``branching`` units (it evaluates every
successor; the caller passes the first search's successors per expansion), and
``PNGS_UNITS`` are charged per ``pngs.CHECK_EVERY`` states the neighborhood
search adds or closes (the points where both ask to stop, in C and in Python
alike).  On the kernel, over benchmarks/classical's first two instances per
domain, a weighted A* expansion took 6-40 us at 3-9 successors, and 1,024
neighborhood states 0.7-1.1 ms, about 500 evaluations.  A task with derived
predicates evaluates its ground rules in every state the neighborhood search
makes, so there a check costs ``PNGS_UNITS`` times ``1 + B / P`` (:func:`pngs_units`:
``B`` the ground rules' condition sizes, ``P`` the actions' precondition sizes):
on IPC-2004 PSR-large p02 (1,080 rules, B = 2,918, P = 189) 1,024 neighborhood
states took about 29 ms of CPU, 28 times the figure above, and the improvement
7.1 of the run's 9.4 s (cProfile, benchmarks/results/ipc_check_ipc10.md).
Without derived predicates the charge is ``PNGS_UNITS`` exactly.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable

from nowplan.planning.axioms import rule_costs
from nowplan.planning.forward import _apply, _goal_reached, _Successors
from nowplan.planning.hff import CostType, RelaxedHeuristic
from nowplan.planning.pngs import improve_by_neighborhood
from nowplan.planning.postprocess import eliminate_actions
from nowplan.planning.task import Task

WEIGHTS = (5.0, 3.0, 2.0, 1.0)
WASTAR_SHARE = 0.25  # of the budget for the weighted A* searches; the rest for the neighborhood search
PNGS_UNITS = 512  # budget units per stop check of the neighborhood search (every pngs.CHECK_EVERY states)


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


def pngs_units(task: Task) -> int:
    """Budget units per stop check of the neighborhood search (module doc): more with derived predicates."""
    ax = task.axioms
    if not ax:
        return PNGS_UNITS
    body = sum(len(b) for b in ax.body)
    pre = max(1, sum(len(p) for p in task.pre))
    return round(PNGS_UNITS * (1 + body / pre))


def improve(task: Task, plan: list[int], budget: int, cost_type: CostType = "plusone",
            out_of_time: Callable[[], bool] = lambda: False, wastar_share: float = WASTAR_SHARE,
            branching: int = 1) -> list[int]:
    """A plan no costlier than ``plan``, searching for at most ``budget`` units of work (module doc).

    ``wastar_share``: the part of the budget for the weighted A* searches (1: no
    neighborhood search, unless they end early).  ``out_of_time`` (the caller's wall-clock
    limit) ends it earlier.
    """
    spent = 0
    end_wastar = wastar_share * budget
    units = pngs_units(task)

    def stop_wastar() -> bool:
        nonlocal spent
        spent += branching
        return spent > end_wastar or out_of_time()

    def stop() -> bool:
        nonlocal spent
        spent += units
        return spent > budget or out_of_time()

    h = RelaxedHeuristic(task, "ff", cost_type)
    succ = _Successors(task, h.native)
    best = plan
    exhausted = False  # weighted A* with w = 1 found no cheaper plan and was not stopped
    for w in WEIGHTS:
        if spent >= end_wastar or out_of_time():
            break
        while True:
            bound = sum(task.cost[a] for a in best)
            if h.native is not None:
                found = h.native.bounded_wastar(task.init, rule_costs(task, task.cost), w, bound, stop_wastar)
            else:
                found = _bounded_wastar(task, h, succ, w, bound, stop_wastar)
            if found is None:
                exhausted = w == 1.0 and spent <= end_wastar and not out_of_time()
                break
            best = eliminate_actions(task, found)
    if exhausted or spent >= budget or out_of_time():
        return best
    return improve_by_neighborhood(task, best, stop, h.native)
