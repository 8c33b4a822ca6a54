"""Plan neighborhood graph search (Nakhost and Müller, ICAPS 2010).

A plan's states ``s0 … sn`` and every state within a few steps of them form
a graph; the cheapest path from ``s0`` to a goal state in that graph is a
plan at most as costly as the given one.  A greedy search's plan often
shuffles an object from hand to hand or takes a detour that no single
action's removal fixes (so greedy action elimination keeps it), but that a
path through the neighborhood short-cuts.

:func:`neighborhood_plan` builds the graph breadth-first from all the plan's
states at once (successors in ascending action order) until it holds
``limit`` states, then runs Dijkstra from ``s0`` over it with the real
action costs.  :func:`improve_by_neighborhood` grows the limit by doubling
while the time lasts, keeping each cheaper plan (with greedy action
elimination after each).  With the compiled kernel the graph and the
shortest path are computed in C (``Kernel.neighborhood``) with the same
result as the Python code below (the reference and fallback).
"""

from __future__ import annotations

import heapq
import itertools
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

from nowplan.planning.forward import _apply, _goal_reached, _Successors
from nowplan.planning.postprocess import eliminate_actions
from nowplan.planning.task import Task

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel

START_LIMIT = 1024  # states in the first neighborhood graph; each round that finds nothing doubles it
MAX_STATES = 1 << 21  # the largest graph, and at most ~MAX_BYTES of state memory
MAX_BYTES = 256 << 20
CHECK_EVERY = 1024  # states between two calls of the time callback


@dataclass
class Neighborhood:
    """The cheapest plan through a neighborhood graph, and whether the graph was all of the reachable space."""

    plan: list[int]
    states: int
    complete: bool
    stopped: bool = False


def neighborhood_plan(task: Task, plan: list[int], limit: int, cost: list[float],
                      stop: Callable[[], bool] = lambda: False, succ: _Successors | None = None) -> Neighborhood:
    """The cheapest plan (under ``cost``) in ``plan``'s neighborhood graph of at most ``limit`` states.

    ``plan`` must be applicable in ``task.init``; the answer is ``plan`` itself
    when nothing in the graph is cheaper (ties keep ``plan``) or ``stop()``
    said so (``stopped``); ``complete``: the graph holds every reachable state,
    so the answer is optimal.
    """
    succ = succ if succ is not None else _Successors(task)
    states = [task.init]
    for a in plan:
        if not all(p in states[-1] for p in task.pre[a]):
            raise ValueError(f"the plan's action {a} is not applicable where it stands")
        states.append(_apply(task, states[-1], a))
    seen: dict[frozenset[int], int] = {}
    order: list[frozenset[int]] = []  # the graph's states by id: the plan's, then breadth-first
    for s in states:
        if s not in seen:
            seen[s] = len(order)
            order.append(s)
    complete = True
    i = 0
    while i < len(order) and complete:
        s = order[i]
        i += 1
        if i % CHECK_EVERY == 0 and stop():
            return Neighborhood(plan, len(order), False, True)
        for a in succ(s):
            t = _apply(task, s, a)
            if t in seen:
                continue
            if len(order) >= limit:
                complete = False
                break
            seen[t] = len(order)
            order.append(t)
    # Dijkstra from s0 over the states in the graph
    best = sum(cost[a] for a in plan)
    g = {0: 0.0}
    parent: dict[int, tuple[int, int]] = {}
    tick = itertools.count()
    heap = [(0.0, next(tick), 0)]
    closed: set[int] = set()
    while heap:
        gv, _, i = heapq.heappop(heap)
        if i in closed:
            continue
        closed.add(i)
        if gv >= best:
            break
        s = order[i]
        if _goal_reached(task, s):
            out: list[int] = []
            while i:
                i, a = parent[i]
                out.append(a)
            out.reverse()
            return Neighborhood(out, len(order), complete)
        if len(closed) % CHECK_EVERY == 0 and stop():
            return Neighborhood(plan, len(order), False, True)
        for a in succ(s):
            j = seen.get(_apply(task, s, a))
            if j is None or j in closed:
                continue
            ng = gv + cost[a]
            if ng < g.get(j, float("inf")):
                g[j] = ng
                parent[j] = (i, a)
                heapq.heappush(heap, (ng, next(tick), j))
    return Neighborhood(plan, len(order), complete)


def improve_by_neighborhood(task: Task, plan: list[int], stop: Callable[[], bool],
                            native: Kernel | None = None) -> list[int]:
    """``plan`` improved by neighborhood graphs of growing size until ``stop()`` (never costlier).

    ``native``: a compiled kernel of ``task`` (a :class:`RelaxedHeuristic`'s) to
    build and search the graphs in C.
    """
    succ = _Successors(task)
    cost = task.cost
    limit = START_LIMIT
    per_state = 8 * ((len(task.facts) + 63) // 64) + 64  # the kernel's bitset, hash slots, ids and costs
    max_limit = min(MAX_STATES, MAX_BYTES // per_state)
    while limit <= max_limit and not stop():
        if native is not None:
            found, n, complete, stopped = native.neighborhood(task.init, plan, limit, cost, stop)
            res = Neighborhood(found, n, complete, stopped)
        else:
            res = neighborhood_plan(task, plan, limit, cost, stop, succ)
        if res.stopped:
            break
        if sum(cost[a] for a in res.plan) < sum(cost[a] for a in plan):
            plan = eliminate_actions(task, res.plan)
            continue  # the same limit around the new plan
        if res.complete:
            break  # the whole reachable space: the plan is optimal
        limit *= 2
    return plan
