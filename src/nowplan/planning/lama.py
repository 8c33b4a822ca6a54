"""LAMA's first iteration: lazy greedy best-first search over h_FF and the landmark count.

Four open lists, served in turn by priority (Richter and Westphal, 2010):
all successors by h_FF, preferred ones by h_FF, all by landmark count,
preferred ones by landmark count.  A successor is preferred if h_FF prefers
the action that makes it (its relaxed plan's applicable actions; FD's
lama-first takes no preferred operators from the landmarks); the initial
state and every later progress (a new best value of either heuristic) give
the preferred lists priority (``BOOST``).
Evaluation is lazy: a successor enters the lists with its parent's values
and is evaluated when it is taken out.  The landmark count is
path-dependent: each state keeps the accepted landmarks of the path that
first reached it.

With the compiled kernel (:mod:`nowplan.planning.native`) the whole loop
runs in C (``Kernel.lama``) with the same plan and counters; the Python
loop below is the reference and fallback.
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable

from nowplan.planning.forward import BOOST, ForwardResult, _apply, _goal_reached, _path, _Successors, native_result
from nowplan.planning.hff import CostType, RelaxedHeuristic
from nowplan.planning.landmarks import LandmarkCount
from nowplan.planning.plan import PlanStatus
from nowplan.planning.task import Task

Entry = tuple[float, int, frozenset[int], int]


def lama_search(
    task: Task,
    *,
    cost_type: CostType = "plusone",
    max_nodes: int = 500_000,
    out_of_time: Callable[[], bool] = lambda: False,
) -> ForwardResult:
    if task.unsolvable:
        return ForwardResult(PlanStatus.UNSOLVABLE, None, task.unsolvable)
    ff = RelaxedHeuristic(task, "ff", cost_type)
    lm = LandmarkCount(task, native=ff.native)
    if ff.native is not None:
        sets = [sorted(d) for d in lm.sets]
        before = [lm.before.get(i, []) for i in range(len(sets))]
        reasonable = [lm.reasonable.get(i, []) for i in range(len(sets))]
        out = ff.native.lama(task.init, max_nodes, sets, before, out_of_time, BOOST, lm.unreachable, reasonable)
        return native_result(task, out, max_nodes)
    succ = _Successors(task)
    init = task.init
    acc0 = lm.initial_accepted()
    h_ff, pref_ff = ff.evaluate(init)
    h_lm, _ = lm.evaluate(init, acc0)
    if h_ff == math.inf or h_lm == math.inf:
        return ForwardResult(PlanStatus.UNSOLVABLE, None, "the goal is unreachable even ignoring deletes",
                             evaluated=ff.evaluations)
    parent: dict[frozenset[int], tuple[frozenset[int], int] | None] = {init: None}
    accepted: dict[frozenset[int], frozenset[int]] = {init: acc0}
    if _goal_reached(task, init):
        return ForwardResult(PlanStatus.SOLVED, [], "", evaluated=ff.evaluations)
    tick = itertools.count()
    queues: list[list[Entry]] = [[], [], [], []]  # ff, ff preferred, lm, lm preferred
    priority = [0, 0, 0, 0]
    best = [h_ff, h_lm]
    expanded = generated = 0

    def expand(state: frozenset[int], hf: float, hl: float, pref: set[int]) -> None:
        nonlocal generated
        for a in succ(state):
            generated += 1
            t = next(tick)
            heapq.heappush(queues[0], (hf, t, state, a))
            heapq.heappush(queues[2], (hl, t, state, a))
            if a in pref:
                heapq.heappush(queues[1], (hf, t, state, a))
                heapq.heappush(queues[3], (hl, t, state, a))

    priority[1] -= BOOST  # the initial state is progress (as in FD): preferred successors first
    priority[3] -= BOOST
    expand(init, h_ff, h_lm, set(pref_ff))
    while any(queues):
        k = min((i for i in range(4) if queues[i]), key=lambda i: priority[i])
        priority[k] += 1
        _, _, parent_state, a = heapq.heappop(queues[k])
        state = _apply(task, parent_state, a)
        if state in parent:
            continue
        parent[state] = (parent_state, a)
        acc = lm.accept(accepted[parent_state], state)
        accepted[state] = acc
        expanded += 1
        if expanded > max_nodes:
            return ForwardResult(PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} states without a plan",
                                 expanded, generated, ff.evaluations)
        if out_of_time():
            return ForwardResult(PlanStatus.TIME_LIMIT, None, "time limit reached", expanded, generated,
                                 ff.evaluations)
        if _goal_reached(task, state):
            return ForwardResult(PlanStatus.SOLVED, _path(task, parent, state), "", expanded, generated,
                                 ff.evaluations)
        hf, pf = ff.evaluate(state)
        if hf == math.inf:
            continue
        hl, _ = lm.evaluate(state, acc)
        progress = False
        if hf < best[0]:
            best[0] = hf
            progress = True
        if hl < best[1]:
            best[1] = hl
            progress = True
        if progress:
            priority[1] -= BOOST
            priority[3] -= BOOST
        expand(state, hf, hl, set(pf))
    return ForwardResult(PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan", expanded, generated,
                         ff.evaluations)
