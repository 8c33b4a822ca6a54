"""Abstract actions that carry an estimate of what their hidden preconditions cost.

At an abstraction level an action's preconditions of low criticality are not checked, so a
forward search there sees it at its own cost only: on IPC transport (road lengths as costs) a
``drop`` whose truck must first drive to the place costs 1 at the top level, whichever truck and
wherever it is, and the plan hands packages to trucks without regard to where they stand.  Below
the root it is worse: refining one instance of ``drop`` exposes its truck's position, while its
siblings (the same drop with other capacity counts, or by the other truck) still hide theirs,
and the cheapest plan for the refinement swaps them in, driving the trucks back and forth
(``benchmarks/results/auto_ipc/README.md``, "Costs").

The criticalities (ABSTRIPS-, ALPINE-style) say what a level hides, not what it will cost; HPN
(seed 000) costs an abstract operator by an estimate of its refinement.  Here an action that hides preconditions costs its
own cost plus ``h_max`` of the hidden ones (those of its full precondition not in its row at
this level), computed in the concrete relaxed task from the call's initial state: the cheapest
relaxed way to make the hardest hidden precondition true from where things are now (for a
drop, the truck's road distance to the place).  A primitive action keeps its cost, so a
one-level call is unchanged, and so is the cost the executive reports (it sums executed
actions).  The estimate is optimistic for one action alone (it is admissible for the hidden
conjunction) but is made from the call's initial state: a later step of the same abstract plan
is costed from where things are at the start, not after the earlier steps' refinements.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence


def hmax_costs(n_facts: int, init: frozenset[int], pre: Sequence[Sequence[int]],
               add: Sequence[Sequence[int]], cost: Sequence[float]) -> list[float]:
    """``h_max`` of every fact from ``init`` (inf: unreachable) over the actions ``pre``/``add``/
    ``cost`` (a Dijkstra over facts: an action fires once the last of its preconditions is settled,
    at that fact's cost plus its own)."""
    h = [math.inf] * n_facts
    waiting = [len(p) for p in pre]
    need: dict[int, list[int]] = {}
    queue: list[tuple[float, int]] = []
    for f in init:
        h[f] = 0.0
        queue.append((0.0, f))
    heapq.heapify(queue)

    def fire(k: int, base: float) -> None:
        c = base + cost[k]
        for g in add[k]:
            if c < h[g]:
                h[g] = c
                heapq.heappush(queue, (c, g))

    for k, p in enumerate(pre):
        if not p:
            fire(k, 0.0)
        for f in p:
            need.setdefault(f, []).append(k)
    done = [False] * n_facts
    while queue:  # bounded: each fact is settled once, each action fires once
        c, f = heapq.heappop(queue)
        if done[f] or c > h[f]:
            continue
        done[f] = True
        for k in need.get(f, ()):
            waiting[k] -= 1
            if waiting[k] == 0:
                fire(k, c)
    return h


def add_hidden_costs(n_facts: int, init: frozenset[int], pre: Sequence[Sequence[int]],
                     full_pre: Sequence[Sequence[int]], add: Sequence[Sequence[int]],
                     cost: Sequence[float]) -> list[float] | None:
    """Each action's ``cost`` plus ``h_max`` (over the concrete rows ``full_pre``, from ``init``)
    of its preconditions in ``full_pre`` but not in ``pre``; ``None`` when no action hides one
    (a concrete task: its costs stand).  A hidden precondition that is unreachable, or a fact id
    -1 (an atom the task does not index), adds nothing: such an action cannot be refined from here,
    which the refinement finds out; the estimate is for choosing among refinable ones."""
    hidden = [tuple(f for f in fp if f not in p) for p, fp in zip(pre, full_pre)]
    if not any(hidden):
        return None
    # an atom the task does not index (-1) becomes one fact more that nothing adds: the action never fires
    rows = [tuple(f if f >= 0 else n_facts for f in fp) for fp in full_pre]
    h = hmax_costs(n_facts + 1, init, rows, add, cost)
    out = list(cost)
    for k, hid in enumerate(hidden):
        est = 0.0
        for f in hid:
            if 0 <= f < n_facts and h[f] != math.inf and h[f] > est:
                est = h[f]
        out[k] += est
    return out
