"""A* over subgoals, backwards from a goal: the regression planner's search loop.

One call of :meth:`nowplan.planning.regression_search._Search.run`: the frontier's entries are
``(f, h, r, idle, stamp, seq, item)`` (ties of ``(f, h)`` broken as :mod:`nowplan.planning.rewrites`
says), the items nodes ``(fact ids, focus)`` or the deferred and postponed successors of
:mod:`nowplan.planning.deferred`. ``order`` serializes the goal (seed 002 V-B: the atoms before the
focus are left out of the search), ``protect`` makes it monotonic (no step may change those atoms).
"""

from __future__ import annotations

import heapq
import itertools
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from nowplan.core.atoms import Atom, Goal
from nowplan.core.operators import Action
from nowplan.planning.deferred import Deferred, Expansion, Postponed, Reach, Stamp, kept_cost
from nowplan.planning.hadd_kernel import KernelHadd
from nowplan.planning.plan import PlanStatus
from nowplan.planning.preimage import preimage
from nowplan.planning.rewrites import pure_rewrite
from nowplan.planning.subgoals import ActionFacts, GoalOf, NodeIndex, regress

if TYPE_CHECKING:
    from nowplan.planning.regression_search import _Search


def astar(
    search: _Search,
    goal: Goal,
    max_nodes: int,
    order: Sequence[Atom] | None = None,
    protect: frozenset[Atom] = frozenset(),
) -> tuple[PlanStatus, list[tuple[Action | None, Goal]] | None, str]:
    """A* from ``goal``; ``order`` = serialization, ``protect`` = monotonic atoms.

    With a relaxed estimate that bounds (h_max, LM-cut, h_add over the lazy
    relaxation), the successors of the facts that already hold are deferred
    (:mod:`nowplan.planning.deferred`): made only when their entry comes first.
    """
    T = search.table
    fluent = T.fluent
    root = T.ids_of(goal.atoms)
    root_ok = T.consistent(root)  # else its successors are computed on Goals (see subgoals)
    order_ids = [T.id(a) for a in order] if order is not None else None
    # the atoms left out of the search while the focus is k: order[: k - 1], i.e. those whose first
    # position in the order is below k - 1 (by position: sets for every focus took O(n²) per call)
    pos: dict[int, int] = {}
    for i, f in enumerate(order_ids or ()):
        pos.setdefault(f, i)
    pos_of, never = pos.get, len(order_ids or ()) + 1
    guard = {fluent[f]: f for f in T.ids_of(protect)}
    focus0 = len(order) if order is not None else 0
    counter = itertools.count()
    Node = tuple[frozenset[int], int]
    start: Node = (root, focus0)
    h0 = search.h(root)
    # entries (f, h, r, idle, stamp, seq, node or Deferred), ties of (f, h) broken by (see rewrites.py):
    # r, the pure rewrites of held facts on the path; idle, 1 if the step sets no unmet fact of its
    # parent; the stamp, eager generation's order (deferred)
    first: Stamp = (-1, 0, 0)
    frontier: list[tuple[float, float, int, int, Stamp, int, Node | Deferred | Postponed]] = [
        (search.config.weight * h0, h0, 0, 0, first, next(counter), start)]
    best_g: dict[Node, float] = {start: 0.0}
    # per node pushed: its estimate and its rewrites (a pure rewrite child has its parent's unmet facts)
    meta: dict[Node, tuple[float, int]] = {start: (h0, 0)}
    # per node pushed: the least (r, idle, stamp) of its paths of its cost so far, its key's tail: the
    # same in eager and deferred search (an entry that could give a lesser one comes first)
    tails: dict[Node, tuple[int, int, Stamp]] = {start: (0, 0, first)}
    born: dict[Node, Stamp] = {start: first}
    parent: dict[Node, tuple[Node, Action] | None] = {start: None}
    closed: set[Node] = set()
    levels, drop, weight = search.levels, search.drop, search.config.weight
    hvals = search.hadd.values.__getitem__ if isinstance(search.hadd, KernelHadd) and not callable(search.domain_h) else None
    relaxed = search.relaxed if not callable(search.domain_h) else None
    defer = search.defer_held and relaxed is not None and relaxed.kind in ("max", "lmcut", "add")
    reach = Reach(search.domain) if defer else None
    exp = 0
    regress_, forbidden, inf, push, fholds = regress, search.forbidden_first, math.inf, heapq.heappush, search.fholds
    held = search._held  # (facts fholds found true)
    no_rewrites = not search.config.held_rewrites
    inherit_h = not callable(search.domain_h)  # (a domain's own estimate may read more than the unmet facts)
    pairs = search.pairs()
    if pairs is not None and pairs.excluded(root):
        return PlanStatus.UNSOLVABLE, None, "the goal holds facts no reachable state holds together (h2)"

    def make(node: Node, focus: int, gcost: float, index: NodeIndex, goal_of: Callable[[], Goal], legacy: bool,
             act: Action, info: ActionFacts, cost: float, st: Stamp) -> None:
        """Regress ``node`` through ``act`` and push the child (eager search's body for one successor)."""
        if guard and any(guard.get(fluent[e], e) != e for e in info.all_effs):
            return
        if not legacy:
            pre = regress_(T, index, info)
        else:
            g = preimage(goal_of(), act, levels.level(act), search.domain, drop)
            pre = None if g is None else T.ids_of(g.atoms)
        if pre is None:
            return
        if pairs is not None and pairs.excluded(pre, pre.difference(node[0])):
            return  # two facts no reachable state holds together (planning/h2.py)
        rewrite = cost == 0.0 and pure_rewrite(node[0], pre, fholds)
        if rewrite and no_rewrites:
            return  # a zero-cost rewrite of held facts into held facts (PlannerConfig.held_rewrites)
        if forbidden and act.key in forbidden and search.satisfied(pre):
            return  # it would be the plan's first step: learnt not to be refinable from here
        child = (pre, focus)
        ng = gcost + cost
        old = best_g.get(child, inf)
        if ng > old or ng == inf:  # (an infinite cost: never kept, as eager search's ng >= old)
            return
        hp, r = meta[node]
        if rewrite:
            r += 1
        idl = 1  # (rewrites.idle, inlined: once per child)
        nf = index.by_fluent
        for flu, _ in info.eff_fl:
            o = nf.get(flu)
            if o is not None and o not in held and not fholds(o):
                idl = 0
                break
        tail = (r, idl, st)
        if ng == old:  # eager generation keeps the path it made first, and the least (r, idle, stamp)
            if st < born[child]:
                born[child] = st
                parent[child] = (node, act)
            if child in closed or child not in tails or tail >= tails[child]:
                return
            hh = meta[child][0]
        elif child in closed:
            return
        else:
            best_g[child] = ng
            born[child] = st
            parent[child] = (node, act)
            search.generated += 1
            if rewrite and inherit_h:
                hh = hp  # the same unmet facts: the estimate of what they cost (see rewrites.py)
            elif hvals is not None:
                try:  # the kernel's values: every fact valued, 0 where it holds
                    hh = sum(map(hvals, pre))
                except IndexError:
                    hh = search.h(pre)
            else:
                hh = search.h(pre)
            if hh == inf:
                return  # an atom of the pre-image is unreachable
        meta[child] = (hh, r)
        tails[child] = tail
        push(frontier, (ng + weight * hh, hh, *tail, next(counter), child))

    while frontier:
        top = heapq.heappop(frontier)
        item = top[6]
        if isinstance(item, Postponed):  # unmet facts' successors whose bound has come first
            for act, info, cost, st in item.items:
                make(item.node, item.focus, item.g, item.index, item.goal_of, False, act, info, cost, st)
            continue
        if isinstance(item, Deferred):  # ground the held targets and make their successors
            x = item.expansion
            for ti, target in item.targets:
                for j, (act, info, cost) in enumerate(search._successors(target, x.goal_of)):
                    if id(act) in x.tried or search._listed_before(x, act, info, ti) is not None:
                        continue  # made already, or an earlier target's (made when that one is)
                    x.tried.add(id(act))
                    make(x.node, x.focus, x.g, x.index, x.goal_of, False, act, info, cost, (x.number, ti, j))
            continue
        node = item
        if node in closed:
            continue
        closed.add(node)
        fs, focus = node
        if order_ids is not None:
            # shift the focus down once the non-focused part already holds
            if focus > 0:  # (down to the focus below which the unmet atoms are no longer all hidden)
                last = max([pos_of(u, never) for u in search.unmet(fs)], default=-1)
                if last < focus - 1:
                    focus = last + 1
        if search.satisfied(fs):
            return PlanStatus.SOLVED, search._path(node, parent), ""
        exp += 1
        search.expanded += 1
        if exp > max_nodes:
            return PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} nodes without a plan"
        if search.gave_up is not None and not exp & 63:
            why = search.gave_up()
            if why is not None:
                return PlanStatus.NODE_LIMIT, None, why
        if search.now() > search.deadline:
            return PlanStatus.TIME_LIMIT, None, f"time limit of {search.config.time_limit:g} s reached"
        gcost = best_g[node]
        hnode, rnode = meta[node]
        if order_ids is not None and focus > 1:
            cut = focus - 1
            allowed = [f for f in T.sorted(fs) if pos_of(f, never) >= cut]
        else:
            allowed = T.sorted(fs)
        index = NodeIndex(T, fs)
        goal_of = GoalOf(T, fs)
        legacy = not root_ok and fs == root
        tried: set[int] = set()  # by identity: the grounder makes one object per instance
        here: Expansion | None = None
        later: dict[tuple[float, float, int], list[tuple[int, int]]] = {}  # held targets by their bound
        unmet_ids: list[tuple[int, float]] | None = None  # the node's unmet facts with their explored costs
        postponed: dict[tuple[float, float], list[tuple[Action, ActionFacts, float, Stamp]]] = {}
        postpone = search.postpone_unmet and reach is not None and not legacy
        for ti, target in enumerate(allowed):
            if reach is not None and not legacy and (target in held or fholds(target)):
                if unmet_ids is None:
                    assert relaxed is not None
                    unmet_ids = [(f, relaxed.known(f)) for f in search.unmet(fs)]
                c, b, kept = reach.bound_all(target, unmet_ids, hnode)
                if b != inf:  # else every child keeps a fact proven unreachable
                    later.setdefault((c, b, int(kept)), []).append((ti, target))
                continue
            for j, (act, info, cost) in enumerate(search._successors(target, goal_of)):
                if id(act) in tried:
                    continue
                st = (exp, ti, j)
                if later:  # a held target before this one may list it: eager search made it there
                    if here is None:
                        here = Expansion(node, focus, gcost, index, goal_of, allowed, tried, exp)
                    earlier = search._listed_before(here, act, info, ti)
                    if earlier is not None:
                        st = (exp, earlier[0], earlier[1])
                tried.add(id(act))
                if postpone:  # a child whose bound lies above this node's (f, h) waits in an entry
                    if unmet_ids is None:
                        assert relaxed is not None
                        unmet_ids = [(f, relaxed.known(f)) for f in search.unmet(fs)]
                    b = kept_cost(fluent, info, unmet_ids)
                    key = (gcost + cost + weight * b, b)
                    if key > (top[0], top[1]):
                        postponed.setdefault(key, []).append((act, info, cost, st))
                        continue
                make(node, focus, gcost, index, goal_of, legacy, act, info, cost, st)
        for (fb, b), items in postponed.items():
            push(frontier, (fb, b, rnode, 0, min(x[3] for x in items), next(counter),
                            Postponed(node, focus, gcost, index, goal_of, items)))
        if later:
            if here is None:
                here = Expansion(node, focus, gcost, index, goal_of, allowed, tried, exp)
            for (c, b, kept_all), targets in later.items():  # (g + c + w·b, b, r, idle) is at most each child's key
                push(frontier, (gcost + c + weight * b, b, rnode, kept_all, (exp, targets[0][0], 0), next(counter),
                                Deferred(here, targets)))
    return PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan at this level"

