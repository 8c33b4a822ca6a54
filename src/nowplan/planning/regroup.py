"""Regrouping an abstract plan by what its steps hide: deorder, then relinearize (the ``regroup`` switch).

At an abstraction level an action's low-criticality preconditions are not checked, so every order
of independent abstract steps costs the same there, and the planner returns one of them.  Their
refinements do not cost the same: on gripper (``at-robby`` hidden at the top) the top-level plan
``pick b1, pick b2, drop b1, pick b3, drop b2, …`` sends the robot across the room between any two
steps (4 actions a ball), while ``pick b1, pick b2, drop b1, drop b2, …`` carries two balls a trip
(3 a ball, as a concrete plan does).  This module reorders a plan so that consecutive steps ask
the same of the hidden fluents:

1. *Deorder* (the causal-link partial order of a sequential plan, as in Kambhampati and Kedar's
   explanation-based generalisation and Bäckström's deorderings): each precondition a step checks
   at its level, and each atom of the goal, is linked to the latest earlier step with an effect on
   its fluent (or to the initial belief); every other step whose effect on that fluent does not
   give the linked value is kept before the producer or after the consumer, as it was.  Every
   linearization of these orderings is a plan at the same levels (the classical soundness of
   causal-link plans without threats).
2. *Relinearize* greedily: keep a context of the hidden fluents' values (the belief's, then those
   the steps placed so far needed or set, with the domain's mutex groups: needing
   ``at-robby(roomb)`` makes ``at-robby(rooma)`` false).  Among the steps whose predecessors are
   placed, the planner's next one (the earliest in its order) goes next unless it disagrees with
   the context and a later one disagrees less while agreeing on at least one hidden precondition:
   then the one that disagrees least (the earliest among equals).  A step with nothing hidden, or
   nothing in common with the context, is never pulled ahead (the mill shop's parking moves,
   pulled to the front, made every refinement after them drive the AGVs home again).

The plan keeps its actions (the abstract cost is the same), and its pre-images are computed again
by regression through the new order (:func:`nowplan.planning.forward.regress_actions`); a result that
does not regress from the belief (a domain whose effects leave conflicts to its rules) or that
changes nothing is dropped, and the planner's plan stands.  Plans of concrete steps only, plans with
derived predicates and plans longer than :data:`MAX_STEPS` are left alone.
"""

from __future__ import annotations

import bisect
import logging
from collections.abc import Callable, Sequence
from typing import Any

from nowplan.core.atoms import Atom, Goal, _keyed, group_keys_of
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action

log = logging.getLogger(__name__)

MAX_STEPS = 5_000  # longer plans are left as found (the deordering is quadratic in the worst case)
MAX_EDGE_WORK = 2_000_000  # threat tests over the plan: past this, the plan is left as found


def deorder(
    domain: Domain, actions: Sequence[Action], levels: LevelMap, goal: Goal
) -> list[set[int]] | None:
    """The successors of each step in the causal-link partial order of ``actions`` (indices 0..n-1).

    ``None`` if the sequence is not a plan by its own effects (a checked precondition whose latest
    effect on its fluent gives another value), or the threat tests pass :data:`MAX_EDGE_WORK`.
    """
    rules = domain.rules
    statics = domain.static_predicates
    by_key: dict[Any, list[tuple[int, Atom]]] = {}  # fluent -> (step, effect) in plan order
    for i, a in enumerate(actions):
        for e in a.effects():
            by_key.setdefault(e.key, []).append((i, e))
    succ: list[set[int]] = [set() for _ in actions]
    work = 0

    def link(p: Atom, j: int) -> bool:
        """Order the producer of ``p`` for step ``j`` (``len(actions)``: the goal) and its threats."""
        nonlocal work
        effs = by_key.get(p.key)
        if not effs:
            return True  # the belief's, and no step touches it
        pos = bisect.bisect_left(effs, j, key=lambda t: t[0]) - 1  # the latest effect before j
        rule = rules.rule(p.predicate)
        producer = -1
        if pos >= 0:
            i, e = effs[pos]
            if not rule.entails(e.value, p.value):
                return False
            producer = i
            if i != j:
                succ[i].add(j)
        work += len(effs)
        if work > MAX_EDGE_WORK:
            return False
        for k, e in effs:
            if k == producer or k == j or rule.entails(e.value, p.value):
                continue
            if k < producer:
                succ[k].add(producer)
            elif k > j:
                succ[j].add(k)
        return True

    n = len(actions)
    for j, a in enumerate(actions):
        for p in a.preconditions(levels.level(a)):
            if p.predicate not in statics and not link(p, j):
                return None
    for p in goal.atoms:
        if p.predicate not in statics and p.predicate not in domain.derived and not link(p, n):
            return None
    for s in succ:
        s.discard(n)
    return succ


class _Context:
    """The values of the hidden fluents as the steps placed so far leave them (see the module text)."""

    def __init__(self, domain: Domain, holds: Callable[[Atom], bool]) -> None:
        self.rules = domain.rules
        self.holds = holds
        self.keyed, _, self.memo = _keyed(domain.rules)
        self.value: dict[Any, Any] = {}  # fluent -> value needed or set last
        self.owner: dict[Any, Atom] = {}  # mutex group -> the atom made true in it last

    def agrees(self, h: Atom) -> bool:
        v = self.value.get(h.key, _UNSET)
        if v is not _UNSET:
            return bool(self.rules.rule(h.predicate).entails(v, h.value))
        if h.value is True and self.keyed:
            for g in group_keys_of(h, self.keyed, self.memo):
                o = self.owner.get(g)
                if o is not None and o.key != h.key:
                    return False
        return self.holds(h)

    def set(self, a: Atom) -> None:
        self.value[a.key] = a.value
        if a.value is True and self.keyed:
            for g in group_keys_of(a, self.keyed, self.memo):
                o = self.owner.get(g)
                if o is not None and o.key != a.key:
                    self.value.pop(o.key, None)  # no longer true: the group's owner says so
                self.owner[g] = a


_UNSET = object()


def hidden_preconditions(a: Action, levels: LevelMap, statics: frozenset[str] | set[str]) -> tuple[Atom, ...]:
    """The preconditions ``a`` does not check at its level in ``levels`` (static ones left out)."""
    kept = set(a.preconditions(levels.level(a)))
    return tuple(p for p in a.preconditions(None) if p not in kept and p.predicate not in statics)


def relinearize(
    domain: Domain, actions: Sequence[Action], hidden: Sequence[tuple[Atom, ...]], succ: list[set[int]],
    holds: Callable[[Atom], bool],
) -> list[int]:
    """A linearization of the partial order ``succ`` placing steps that agree with the context first
    (``hidden``: each step's :func:`hidden_preconditions`)."""
    n = len(actions)
    indeg = [0] * n
    for s in succ:
        for k in s:
            indeg[k] += 1
    ready = [i for i in range(n) if indeg[i] == 0]
    ctx = _Context(domain, holds)
    order: list[int] = []
    while ready:
        # the planner's next step, unless a later ready one continues the context and disagrees less
        best, best_miss = 0, sum(1 for h in hidden[ready[0]] if not ctx.agrees(h))
        for r in range(1, len(ready)):
            if best_miss == 0:
                break
            hs = hidden[ready[r]]
            miss = sum(1 for h in hs if not ctx.agrees(h))
            if miss < best_miss and miss < len(hs):
                best, best_miss = r, miss
        i = ready.pop(best)
        order.append(i)
        for h in hidden[i]:
            ctx.set(h)
        for e in actions[i].effects():
            ctx.set(e)
        for k in succ[i]:
            indeg[k] -= 1
            if indeg[k] == 0:
                bisect.insort(ready, k)
    return order


def regroup(
    domain: Domain, belief: Any, goal: Goal, actions: Sequence[Action], levels: LevelMap,
) -> list[tuple[Action | None, Goal]] | None:
    """The plan's steps ``[(None, g0), (a1, g1), …]`` in a regrouped order, or ``None`` (keep the plan:
    nothing is hidden, nothing moves, the deordering does not apply, or the result does not regress)."""
    from nowplan.planning.forward import regress_actions

    n = len(actions)
    if n < 3 or n > MAX_STEPS or domain.axioms or domain.derived:
        return None
    hidden = [hidden_preconditions(a, levels, domain.static_predicates) for a in actions]
    if not any(hidden):
        return None
    succ = deorder(domain, actions, levels, goal)
    if succ is None:
        return None
    order = relinearize(domain, actions, hidden, succ, lambda a: domain.holds(a, belief))
    if order == list(range(n)) or len(order) != n:
        return None
    steps = regress_actions(domain, belief, goal, [actions[i] for i in order], levels)
    if steps is None:
        log.info("regrouped plan of %d steps does not regress from the belief: the planner's order stands", n)
        return None
    log.info("regrouped a plan of %d steps by its hidden preconditions", n)
    return steps
