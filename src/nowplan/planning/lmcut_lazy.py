"""LM-cut (Helmert & Domshlak 2009) over the lazy relaxation's explored achievers, on a pruned graph.

:func:`lmcut_part` is :meth:`LazyRelaxed.lmcut`'s work for one group of goal
facts: repeatedly h_max with the current costs, the cut of actions leading
from the facts that hold into the goal zone of the justification graph (each
action's most expensive precondition), add the cheapest cost in the cut and
take it off every action of the cut.  Admissible where h_max is.

The graph it runs on (:func:`cut_graph`) leaves out what cannot change the
value, so its size follows the facts the goal needs rather than every
object an achiever could name (unloading *any* package frees a vehicle's
door, so the door's achievers grow with the packages):

* a fact whose explored cost is 0 is a source, like a fact that holds: its
  h_max stays 0 as costs fall and no goal zone holds it, so an action that
  is in the graph only as its achiever (every target it has there costs 0)
  is in no cut and lowers no other fact;
* an achiever ``b`` of a fact ``e`` is left out when the first cheapest
  achiever ``a`` of ``e`` whose preconditions all cost 0 costs no more and
  has every target of ``b`` in the graph among its own: ``a`` is in every
  cut ``b`` is in (its most expensive precondition is a source), so ``b``
  costs at least as much as ``a`` throughout, never lowers a fact's h_max,
  never brings a fact into the goal zone (at cost 0 its targets would cost
  0) and never sets a cut's minimum.

With ties in h_max broken by fact id, each action's most expensive
precondition depends on the costs alone, so the pruned graph gives the
value of the whole one (``tests/test_heuristics.py`` compares them).
"""

from __future__ import annotations

import heapq
import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nowplan.planning.relaxed import LazyRelaxed


def cut_graph(r: LazyRelaxed, goal: list[int]) -> tuple[set[int], list[int], list[int]]:
    """The facts behind ``goal``, the actions LM-cut needs (see the module docstring) and the sources."""
    val, pre_of, cost_of, targets_of, achieved_by = r.val, r._pre, r._cost, r._targets, r._achieved_by
    facts, stack = set(goal), list(goal)
    acts: list[int] = []
    kept: set[int] = set()
    init: list[int] = []
    pending: list[tuple[int, frozenset[int]]] = []  # (achiever left out, its dominator's targets)

    def keep(a: int) -> None:
        kept.add(a)
        acts.append(a)
        for p in pre_of[a]:
            if p not in facts:
                facts.add(p)
                stack.append(p)

    while True:
        while stack:
            f = stack.pop()
            if val.get(f) == 0.0:
                init.append(f)
                continue
            ach = [a for a in achieved_by.get(f, ()) if all(p in val for p in pre_of[a])]  # those that can fire
            best, bc = -1, math.inf
            for a in ach:
                if cost_of[a] < bc and all(val[p] == 0.0 for p in pre_of[a]):
                    best, bc = a, cost_of[a]
            cover = frozenset(targets_of[best]) if best >= 0 else frozenset()
            for a in ach:
                if a in kept:
                    continue
                if best >= 0 and a != best and cost_of[a] >= bc:
                    pending.append((a, cover))
                else:
                    keep(a)
        # an achiever left out comes back if one of its targets joined the graph outside its dominator's
        rest: list[tuple[int, frozenset[int]]] = []
        for a, cover in pending:
            if a in kept:
                continue
            if any(t in facts and t not in cover for t in targets_of[a]):
                keep(a)
            else:
                rest.append((a, cover))
        pending = rest
        if not stack:
            return facts, acts, init


def lmcut_part(r: LazyRelaxed, goal: list[int], prune: bool = True) -> float:
    """LM-cut of ``goal``'s facts (all reached, none costing 0) over the pruned graph (``prune=False``: the whole one)."""
    facts, acts, init = cut_graph(r, goal) if prune else r._relevant(goal)
    pre_of = r._pre
    cost = {a: r._cost[a] for a in acts}
    users: dict[int, list[int]] = {}
    for a in acts:
        for p in pre_of[a]:
            users.setdefault(p, []).append(a)
    targets = {a: [t for t in r._targets[a] if t in facts] for a in acts}
    achieved: dict[int, list[int]] = {}
    for a in acts:
        for t in targets[a]:
            achieved.setdefault(t, []).append(a)
    total = 0.0
    for _ in range(len(acts) + 1):
        h, pcf = hmax_over(pre_of, init, acts, cost, users, targets)
        top = max(goal, key=lambda u: h.get(u, math.inf))
        g = h.get(top, math.inf)
        if g == 0.0 or g == math.inf:
            break
        zone, todo = {top}, [top]  # facts from which the goal is reached at zero cost
        while todo:
            e = todo.pop()
            for a in achieved.get(e, ()):
                x = pcf.get(a)
                if cost[a] == 0.0 and x is not None and x >= 0 and x not in zone:
                    zone.add(x)
                    todo.append(x)
        by_pcf: dict[int, list[int]] = {}
        for a, x in pcf.items():
            by_pcf.setdefault(x, []).append(a)
        reach = set(init)
        reach.add(-1)
        todo = [*init, -1]
        cut: list[int] = []
        while todo:
            x = todo.pop()
            for a in by_pcf.get(x, ()):
                into = False
                for e in targets[a]:
                    if e in zone:
                        into = True
                    elif e not in reach:
                        reach.add(e)
                        todo.append(e)
                if into:
                    cut.append(a)
        if not cut:
            break
        m = min(cost[a] for a in cut)
        total += m
        for a in cut:
            cost[a] -= m
    return total


def hmax_over(
    pre_of: list[tuple[int, ...]],
    init: list[int],
    acts: list[int],
    cost: dict[int, float],
    users: dict[int, list[int]],
    targets: dict[int, list[int]],
) -> tuple[dict[int, float], dict[int, int]]:
    """h_max of the facts with ``cost``; each fired action's most expensive precondition (-1: none).

    Ties are broken by fact id (facts of equal cost pop in id order), so the
    most expensive precondition depends on the costs alone, not on the order
    in which the graph's actions were listed.
    """
    h: dict[int, float] = {}
    pcf: dict[int, int] = {}
    missing = {a: len(pre_of[a]) for a in acts}
    heap: list[tuple[float, int]] = [(0.0, f) for f in init]
    for a in acts:
        if not pre_of[a]:
            pcf[a] = -1
            for t in targets[a]:
                heap.append((cost[a], t))
    heapq.heapify(heap)
    while heap:
        v, f = heapq.heappop(heap)
        if f in h:
            continue
        h[f] = v
        for a in users.get(f, ()):
            missing[a] -= 1
            if missing[a] == 0:
                pcf[a] = f  # popped last: the most expensive precondition
                x = cost[a] + v
                for t in targets[a]:
                    if t not in h:
                        heapq.heappush(heap, (x, t))
    return h, pcf
