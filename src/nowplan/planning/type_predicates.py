"""Types read from static unary predicates, for the automatic hierarchy of untyped domains.

Untyped STRIPS domains (IPC driverlog, logistics-98/00, mystery, mprime) state an
argument's kind as a static unary precondition: ``(truck ?t)``, ``(obj ?o)``.  Without
types every ``at`` literal is one class in :mod:`nowplan.planning.abstraction`, so a
package's position is tied to a truck's and the hierarchy has one level.  Knoblock's
ALPINE typed its literals the same way (the domain's types); here an untyped operator
parameter gets the *type set* of the static unary predicates the operator requires of it
(``[truck]``; none: any object).  Two type sets can hold of one object unless they differ
with neither a subset of the other; from the domain alone such sets are taken to be
disjoint (as different types are), and :func:`shared_objects` checks a problem's objects:
where one object has both, the problem's hierarchy merges exactly the classes whose type sets
share an object (:func:`nowplan.planning.problem_hierarchy.problem_hierarchy`).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from nowplan.core.atoms import Var
from nowplan.core.domain import Domain, Problem
from nowplan.core.operators import Operator
from nowplan.core.state import State

PREFIX = "["  # a type set's name, "[obj]" or "[location,obj]": no PDDL type name has a bracket


def is_type_set(name: str) -> bool:
    return name.startswith(PREFIX)


def members(name: str) -> frozenset[str]:
    """The predicates of a type set's name."""
    return frozenset(name[1:-1].split(","))


def type_set(domain: Domain, op: Operator, v: Var) -> str:
    """``[p,q]``: the static unary predicates ``op`` requires of its untyped parameter ``v``
    (positively); ``""`` (any object) without any."""
    static = domain.static_predicates
    preds = sorted({p.atom.predicate for p in op.preconditions
                    if len(p.atom.args) == 1 and p.atom.args[0] == v and p.atom.value is True
                    and p.atom.predicate in static})
    return f"{PREFIX}{','.join(preds)}]" if preds else ""


def may_overlap(a: str, b: str) -> bool:
    """From the domain alone: can one object be of both type sets (one a subset of the other)?"""
    x, y = members(a), members(b)
    return x <= y or y <= x


def extension(problem: Problem, name: str) -> frozenset[str]:
    """The objects of ``problem`` that satisfy every predicate of the type set (in its initial state)."""
    init = problem.init
    if not isinstance(init, State):
        return frozenset(problem.all_objects)
    out: set[str] | None = None
    for pred in members(name):
        objs = {args[0] for args in init.facts(pred) if len(args) == 1 and isinstance(args[0], str)}
        out = objs if out is None else out & objs
    return frozenset(out or ())


def shared_objects(problem: Problem, pairs: Iterable[tuple[tuple[str, ...], tuple[str, ...]]]) -> str | None:
    """Where two classes' type sets, taken as disjoint, share an object of ``problem`` at every
    position (so one ground atom would be in both): a note naming the first; ``None`` if none does."""
    ext: dict[str, frozenset[str]] = {}

    def objs(name: str) -> frozenset[str] | None:  # None: any object
        if not is_type_set(name):
            return None
        if name not in ext:
            ext[name] = extension(problem, name)
        return ext[name]

    for xs, ys in pairs:
        if all(_meet(objs(a), objs(b)) for a, b in zip(xs, ys, strict=True)):
            return f"({', '.join(xs)}) and ({', '.join(ys)}) in {problem.name}"
    return None


def _meet(a: frozenset[str] | None, b: frozenset[str] | None) -> bool:
    return a is None or b is None or bool(a & b)


def object_sets(problem: Problem, names: Iterable[str]) -> Mapping[str, frozenset[str]]:
    """Each type set's objects in ``problem`` (for :func:`nowplan.planning.problem_hierarchy.ground_level`)."""
    return {n: extension(problem, n) for n in set(names) if is_type_set(n)}
