"""Deferred successors in the regression search: the achievers of facts that already hold.

A subgoal of HPN's calls holds every goal fact of the objects the call does
not touch (a package already delivered, or waiting where it is); they hold in
the belief, yet A* regresses through each of their achievers too (the last
step of a plan may have to re-achieve a fact an earlier step undid), and
each such successor costs grounding, a pre-image, new facts to explore and
an estimate.  Their number grows with the number of such objects, while they
are almost never expanded: a step that re-achieves a fact that holds adds
its own cost to every unmet fact's.

So when a node is expanded, the successors of the facts it asks for that do
not hold are made at once, and the facts that hold are put, ungrounded, into
:class:`Deferred` frontier entries, with a lower bound on their children's
``(f, h)``: ``(g + c + weight · b, b)``, where ``c`` is the cheapest fixed
cost of an operator with an effect that can entail the fact and ``b`` is the
largest explored cost of an unmet fact of the node that no effect or
precondition of such an operator can name (:class:`Reach`): the regression
keeps that fact in the child as it is, and the relaxed estimates the search
uses with deferral (h_max, LM-cut, h_add) are at least its cost.  An entry is
opened (its facts grounded, their successors made) only when it comes first
in the frontier, so the search expands what it would have expanded eagerly,
in the same order: a child is stamped with the order in which eager
generation makes it, ``(expansion, target, achiever)`` (an action listed by
several facts of a node counts under the first, as eager search's dedup
does), and the stamp breaks ties as eager generation's counter did (also
between two equally cheap paths to one subgoal).  The relaxation's
exploration is lazy, so its costs can fall between an expansion and the
opening of its entries; a bound that turns out too high only changes the
order, never a plan's validity.

The same bound serves the successors of the facts that do not hold
(:class:`Postponed`): once an unmet fact's achievers are grounded, a child
whose ``(g + cost + weight · b, b)`` lies above its parent's ``(f, h)``, with
``b`` the dearest unmet fact of the node that the action leaves as it is
(:func:`kept_cost`), waits in an entry with that priority instead of being
regressed and estimated at once.  Marsupial's ``door(v) = none`` is cleared
by the Unload of every package (cost 10) as well as by the loader (cost 1):
those children grew with the number of packages and were almost never
expanded.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.planning.grounding_index import unify_effect
from nowplan.planning.subgoals import ActionFacts, NodeIndex

# eager generation order of a child: (parent's expansion number, target index, achiever index)
Stamp = tuple[int, int, int]
_ANY = object()  # a pattern's argument that any value matches
Pattern = tuple[str, tuple[Any, ...]]


class Expansion:
    """One expanded node's context, shared by its deferred entries."""

    __slots__ = ("node", "focus", "g", "index", "goal_of", "allowed", "pos", "tried", "number")

    def __init__(self, node: Any, focus: int, g: float, index: NodeIndex, goal_of: Callable[[], Any],
                 allowed: list[int], tried: set[int], number: int) -> None:
        self.node = node
        self.focus = focus  # the children's focus (serialization)
        self.g = g
        self.index = index
        self.goal_of = goal_of
        self.allowed = allowed  # the targets, in eager generation's order
        self.pos = {f: i for i, f in enumerate(allowed)}
        self.tried = tried  # ids of the actions made (or found wanting) for this node
        self.number = number  # the expansion's number (first part of its children's stamps)


class Deferred:
    """Held targets ``(index, fact)`` of one expansion, sharing one priority bound (a frontier entry)."""

    __slots__ = ("expansion", "targets")

    def __init__(self, expansion: Expansion, targets: list[tuple[int, int]]) -> None:
        self.expansion = expansion
        self.targets = targets


class Postponed:
    """Successors of an unmet fact whose bound lies above their parent's: made when the entry comes first.

    ``items`` are ``(action, facts, cost, stamp)`` as eager generation would
    have made them (each already counted as tried for its expansion); the
    entry's priority is ``(g + cost + weight · b, b)`` with ``b`` from
    :func:`kept_cost`, at most every child's ``(f, h)``.
    """

    __slots__ = ("node", "focus", "g", "index", "goal_of", "items")

    def __init__(self, node: Any, focus: int, g: float, index: NodeIndex, goal_of: Callable[[], Any],
                 items: list[tuple[Any, ActionFacts, float, Stamp]]) -> None:
        self.node = node
        self.focus = focus
        self.g = g
        self.index = index
        self.goal_of = goal_of
        self.items = items


def kept_cost(fluent: Sequence[int], info: ActionFacts, unmet: Sequence[tuple[int, float]]) -> float:
    """The largest explored cost of an unmet fact (``(id, cost)``) that regressing through ``info`` keeps.

    A fact whose fluent no effect and no kept precondition of the action sets
    stays in the child as it is, so the child's relaxed estimate (h_max,
    LM-cut, h_add) is at least its cost.
    """
    b = 0.0
    touched: set[int] | None = None
    for u, v in unmet:
        if v > b:
            if touched is None:
                touched = {fluent[e] for e in info.all_effs}
                touched.update(fluent[q] for q in info.pre)
            if fluent[u] not in touched:
                b = v
    return b


class Reach:
    """Per fact: the cheapest fixed cost of an operator that can achieve it, and what such operators name.

    The patterns are the fluents of every effect and precondition of the
    operators with an effect that can entail the fact, with the variables the
    entailment binds filled in (others match any value).  Kept per domain.
    """

    def __init__(self, domain: Domain) -> None:
        self.domain = domain
        self.atoms = domain.facts.atoms
        hit = domain.facts.derived.get("deferral reach")
        if hit is None or hit[0] is not domain.operators:
            hit = domain.facts.derived["deferral reach"] = (domain.operators, {}, {}, {})
        self._memo: dict[int, tuple[float, tuple[Pattern, ...]]] = hit[1]
        self._named: dict[tuple[int, int], bool] = hit[2]  # (target, fact): does an achiever name the fact?
        # per target: its patterns' arguments by (predicate, arity), what _named reads of them
        self._by_pred: dict[int, dict[tuple[str, int], tuple[tuple[Any, ...], ...]]] = hit[3]

    def __call__(self, f: int) -> tuple[float, tuple[Pattern, ...]]:
        hit = self._memo.get(f)
        if hit is None:
            hit = self._memo[f] = self._reach(self.atoms[f])
        return hit

    def _reach(self, target: Atom) -> tuple[float, tuple[Pattern, ...]]:
        cheapest = math.inf
        pats: list[Pattern] = []
        for op in self.domain.operators:
            binds = [b for b in (unify_effect(e, target, self.domain) for e in op.effects) if b is not None]
            if not binds:
                continue
            cheapest = min(cheapest, 0.0 if callable(op.cost) else max(float(op.cost), 0.0))
            named = [*op.effects, *(p.atom for p in op.preconditions)]
            for b in binds:
                for a in named:
                    args = tuple(b.get(x, _ANY) if isinstance(x, Var) else x for x in a.args)
                    pats.append((a.predicate, args))
        return (0.0 if cheapest == math.inf else cheapest), tuple(dict.fromkeys(pats))

    def bound(self, f: int, unmet: Sequence[tuple[int, float]], whole: float = 0.0) -> tuple[float, float]:
        """``(c, b)`` for target ``f`` and the node's unmet ``(fact, explored cost)`` pairs (see :meth:`bound_all`)."""
        c, b, _ = self.bound_all(f, unmet, whole)
        return c, b

    def bound_all(self, f: int, unmet: Sequence[tuple[int, float]], whole: float = 0.0) -> tuple[float, float, bool]:
        """``(c, b, kept)``: ``kept`` when no achiever of ``f`` names an unmet fact of the node.

        Then every child keeps all the unmet facts as they are (no child makes progress on one),
        and ``b`` is at least ``whole``, the node's estimate of them all.
        """
        c, pats = self(f)
        b = 0.0
        named = self._named
        kept = True
        for u, v in unmet:
            if v > b or kept:
                hit = named.get((f, u))
                if hit is None:
                    hit = named[(f, u)] = _named(self.atoms[u], self._index(f, pats))
                if not hit:
                    if v > b:
                        b = v
                else:
                    kept = False
        if kept and whole > b and unmet:
            b = whole
        return c, b, kept


    def _index(self, f: int, pats: tuple[Pattern, ...]) -> dict[tuple[str, int], tuple[tuple[Any, ...], ...]]:
        """``f``'s patterns' arguments by (predicate, arity), in the patterns' order (kept per domain)."""
        index = self._by_pred.get(f)
        if index is None:
            grouped: dict[tuple[str, int], list[tuple[Any, ...]]] = {}
            for pred, args in pats:
                grouped.setdefault((pred, len(args)), []).append(args)
            index = self._by_pred[f] = {k: tuple(v) for k, v in grouped.items()}
        return index


def _named(a: Atom, index: dict[tuple[str, int], tuple[tuple[Any, ...], ...]]) -> bool:
    """Does a pattern (``index``: their arguments by predicate and arity) name ``a``'s fluent?

    (Marsupial's single-origin problems met every pair of a held package fact and an unmet fact of a
    node, thousands per problem, and scanned all of the target's patterns for each.)"""
    y = a.args
    for args in index.get((a.predicate, len(y)), ()):
        if all(x is _ANY or x == z for x, z in zip(args, y)):
            return True
    return False
