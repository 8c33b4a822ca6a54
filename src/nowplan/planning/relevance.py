"""Backward relevance: the operators that can take part in reaching a goal at a level.

An operator is relevant when one of its effects can make a relevant literal true: a goal
literal, or a precondition that a relevant operator keeps at the level (criticality above
it; static predicates are never relevant, no operator changes them).  Literals are compared
by *typed class*: predicate, sign, and per argument the type of the object (goal) or of the
parameter (operators); two classes match when every pair of argument types can hold one
object (single inheritance: one is a subtype of the other, or either is untyped).  This is
a lifted over-approximation of ground relevance, computed without grounding.

Dropping the other operators keeps every plan: an irrelevant action adds no relevant
literal (else it would be relevant), so removing the irrelevant actions from a plan leaves
each relevant literal true wherever it was (its last achiever before that point is kept,
and the actions removed only ever destroy it), and the goal and every kept action's
preconditions are relevant literals.  The plans left are plans of the full task, and their
pre-images (regressed through the plan afterwards, planning/forward.py) are the same.
Fast Downward's translator prunes the same way after grounding; here it happens before, so
the abstract levels of a hierarchy (whose goals hide most of the domain, e.g. where the
lift is in miconic) do not ground what they cannot use.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from nowplan.core.atoms import Atom, Goal, Var
from nowplan.core.domain import Domain
from nowplan.core.operators import Operator

# a literal class: predicate, value (sign), per argument a type name (None: any)
_Class = tuple[str, Any, tuple[str | None, ...]]


# keep every operator when the relevant ones have at least this share of the instances (bounded by the
# typed objects): a later call that needs the rest extends the grounding and builds its task anew, which
# costs more than the little such a pruning saves (satellite: 516 of 528 actions, then all 528)
MOST = 0.8


def _most(domain: Domain, types: Mapping[str, str | None], relevant: set[str]) -> bool:
    """Do the ``relevant`` operators have at least :data:`MOST` of the domain's instances (each
    operator's bounded by the product of its parameters' typed objects)?"""
    count: dict[str | None, int] = {}

    def n(t: str | None) -> int:
        c = count.get(t)
        if c is None:
            ok = domain.subtypes(t) if t is not None else None
            c = count[t] = sum(1 for ot in types.values() if ok is None or ot in ok)
        return c

    size = {op.name: math.prod(n(op.type_of(v)) for v in op.params) for op in domain.operators}
    total = sum(size.values())
    return total == 0 or sum(size[name] for name in relevant) >= MOST * total


def relevant_operators(domain: Domain, objects: Mapping[str, str | None], goal: Goal,
                       level: int, also: Goal | None = None) -> frozenset[str] | None:
    """The names of the operators relevant to ``goal`` (and ``also``) with preconditions kept at ``level``
    (criticality > ``level``); ``None`` where every operator is kept: a domain with axioms, or
    the relevant operators have most of the instances (:data:`MOST`).  Pass the lowest level any action of the call has."""
    if domain.axioms:
        return None  # derived predicates: their rules' conditions would need relevance too
    statics = domain.static_predicates
    types = {**dict(domain.constants), **dict(objects)}
    key = (id(domain.operators), tuple(types.items()), goal, also, level)
    store: dict[Any, tuple[Any, frozenset[str] | None]] = domain.facts.derived.setdefault("relevance", {})
    hit = store.get(key)
    if hit is not None and hit[0] is domain.operators:  # (the operators held: their id is not reused)
        return hit[1]
    sub: dict[str | None, set[str | None]] = {}

    def subtypes(t: str | None) -> set[str | None]:
        s = sub.get(t)
        if s is None:
            s = sub[t] = domain.subtypes(t)
        return s

    def overlap(a: str | None, b: str | None) -> bool:
        return a is None or b is None or a == b or b in subtypes(a) or a in subtypes(b)

    def ground_class(a: Atom) -> _Class:
        return (a.predicate, a.value, tuple(types.get(x) if isinstance(x, str) else None for x in a.args))

    def lifted_class(op: Operator, a: Atom) -> _Class:
        return (a.predicate, a.value, tuple(
            op.type_of(x) if isinstance(x, Var) and x in op.params
            else types.get(x) if isinstance(x, str) else None for x in a.args))

    def matches(c: _Class, d: _Class) -> bool:
        if c[0] != d[0] or len(c[2]) != len(d[2]):
            return False
        if not (c[1] == d[1] or isinstance(c[1], Var) or isinstance(d[1], Var)):
            return False
        return all(overlap(x, y) for x, y in zip(c[2], d[2], strict=True))

    effects = [(op, [lifted_class(op, e) for e in op.effects]) for op in domain.operators]
    atoms = [*goal.atoms, *(also.atoms if also is not None else ())]
    wanted: set[_Class] = {ground_class(a) for a in atoms if a.predicate not in statics}
    todo = list(wanted)
    relevant: set[str] = set()
    while todo:  # each class enters ``todo`` once: bounded by the operators' preconditions
        c = todo.pop()
        for op, classes in effects:
            if op.name in relevant or not any(matches(c, e) for e in classes):
                continue
            relevant.add(op.name)
            for p in op.preconditions:
                if p.criticality > level and p.atom.predicate not in statics:
                    pc = lifted_class(op, p.atom)
                    if pc not in wanted:
                        wanted.add(pc)
                        todo.append(pc)
    out = None if _most(domain, types, relevant) else frozenset(relevant)
    if len(store) >= 64:
        store.pop(next(iter(store)))
    store[key] = (domain.operators, out)
    return out
