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

Only in a domain whose operators do not all cost the same (``varied_costs``, asked of the domain:
one call's relevant actions may cost alike where the domain's do not, the held-out ferry's): its gains were all in domains with
action costs (IPC transport's road lengths, elevators' trips; ``benchmarks/results/auto_ipc/
hidden_costs/``), while with uniform costs the stale estimate made top-level searches harder and
plans dearer: on the 15-crate depots instance the top level failed and the run planned flat (12.4 s
of planning against 1.1 s without the estimate), driverlog-30 planned 2.8 s for cost 249 against
1.3 s for 228 (``benchmarks/results/regroup_c7cf5b6/``, regrouped runs).  Order among abstract steps is
:mod:`nowplan.planning.regroup`'s job.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from nowplan.core.domain import Domain


def hmax_costs(n_facts: int, init: frozenset[int], pre: Sequence[Sequence[int]],
               add: Sequence[Sequence[int]], cost: Sequence[float]) -> list[float]:
    """``h_max`` of every fact from ``init`` (inf: unreachable) over the actions ``pre``/``add``/
    ``cost``: LM-cut's exploration (:func:`nowplan.planning.lmcut_lazy.hmax_over`) over these rows."""
    from nowplan.planning.lmcut_lazy import hmax_over

    users: dict[int, list[int]] = {}
    for k, p in enumerate(pre):
        for f in p:
            users.setdefault(f, []).append(k)
    acts = list(range(len(pre)))
    reached, _ = hmax_over([tuple(p) for p in pre], list(init), acts, dict(enumerate(cost)), users,
                           {k: list(a) for k, a in enumerate(add)})
    h = [math.inf] * n_facts
    for f, v in reached.items():
        h[f] = v
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


def varied_costs(domain: Domain) -> bool:
    """Do the domain's operators not all cost the same constant (a cost read from the state or
    arguments, e.g. PDDL's ``(road-length ?l1 ?l2)``, or two different constants)?  Asked of the
    domain, not of one call's task, whose relevant actions may happen to cost alike."""
    consts: set[float] = set()
    for op in domain.operators:
        if callable(op.cost):
            return True
        consts.add(float(op.cost))
    return len(consts) > 1
