"""Mutex invariants of STRIPS domains, so regression can prune impossible subgoals.

A :class:`MutexGroup` is a set of ``(predicate, key position)`` members; an
atom ``p(a0, a1, ...)`` is a *member* of the group with *key* ``a[pos]``
(or the key ``()`` when the position is ``None``).  The group is an
invariant when in every reachable state at most one member per key is true,
e.g. in logistics ``{at[0], in[0]}`` (a package or vehicle is in one place)
and in blocksworld ``{on[0], ontable[0], holding[0]}`` and
``{handempty, holding}``.

The check is inductive (a simple form of Helmert's invariant synthesis,
restricted to "at most one"): every operator that adds a member must also
delete a member with the same key term that it requires (a positive
precondition), with distinct deleted atoms for distinct added ones, and a
deleted atom may coincide with no other added one.  Then the number of true
members per key never grows, so if the initial state has at most one per
key, so does every reachable state.  Candidates start as single members and
grow by the deleted preconditions that would balance a failing operator.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass

from nowplan.core.atoms import Atom, Term, Var
from nowplan.belief.protocols import ListsFacts
from nowplan.core.domain import Domain
from nowplan.core.operators import Operator

log = logging.getLogger(__name__)

Member = tuple[str, int | None]


@dataclass(frozen=True)
class MutexGroup:
    """At most one true atom per key among these ``(predicate, key position)`` members."""

    members: frozenset[Member]

    def key_of(self, a: Atom) -> tuple[Term, ...] | None:
        """The key of ``a`` if it is a member (positive, of a member predicate), else None."""
        if a.value is not True:
            return None
        for pred, pos in self.members:
            if pred == a.predicate:
                return () if pos is None else (a.args[pos],)
        return None

    def __str__(self) -> str:
        parts = sorted(p if pos is None else f"{p}[{pos}]" for p, pos in self.members)
        return "{" + ", ".join(parts) + "}"


# --------------------------------------------------------------------------- synthesis


def _key_term(a: Atom, group: dict[str, int | None]) -> tuple[Term, ...] | None:
    if a.predicate not in group:
        return None
    pos = group[a.predicate]
    return () if pos is None else (a.args[pos],)


def _distinct_terms(op: Operator, x: Term, y: Term) -> bool:
    """Can ``x`` and ``y`` never denote the same object in an instance of ``op``?"""
    if x == y:
        return False
    if not isinstance(x, Var) and not isinstance(y, Var):
        return True
    for p in op.preconditions:
        a = p.atom
        if a.predicate == "=" and a.value is False and set(a.args) == {x, y}:
            return True
    return False


def _distinct_atoms(op: Operator, a: Atom, b: Atom) -> bool:
    """Are ``a`` and ``b`` different ground atoms in every instance of ``op``?"""
    if a.predicate != b.predicate or len(a.args) != len(b.args):
        return True
    return any(_distinct_terms(op, x, y) for x, y in zip(a.args, b.args, strict=True))


def _balanced(op: Operator, group: dict[str, int | None]) -> tuple[bool, list[Atom]]:
    """Does ``op`` keep the number of members per key from growing?

    Returns ``(ok, unbalanced adds)``.
    """
    adds = [e for e in op.effects if e.value is True and e.predicate in group]
    if not adds:
        return True, []
    required = {p.atom for p in op.preconditions if p.atom.value is True}
    dels = [
        e.negate()
        for e in op.effects
        if e.value is False and e.predicate in group and e.negate() in required
    ]
    # an assignment add -> distinct deleted atom with the same key term (backtracking)
    options = [[d for d in dels if _key_term(d, group) == _key_term(a, group)] for a in adds]
    unbalanced = [a for a, opts in zip(adds, options, strict=True) if not opts]
    if unbalanced:
        return False, unbalanced

    def ok_pair(i: int, d: Atom) -> bool:
        # d must not be re-added by another add effect (add wins over delete)
        return all(j == i or _distinct_atoms(op, d, a) for j, a in enumerate(adds))

    def assign(i: int, used: list[Atom]) -> bool:
        if i == len(adds):
            return True
        for d in options[i]:
            if ok_pair(i, d) and all(_distinct_atoms(op, d, u) for u in used):
                if assign(i + 1, [*used, d]):
                    return True
        return False

    return assign(0, []), []


def _extensions(
    op: Operator, group: dict[str, int | None], add: Atom
) -> Iterator[tuple[str, int | None]]:
    """Members whose addition to ``group`` could balance ``add`` in ``op``."""
    keyed = next(iter(group.values())) is not None
    key = _key_term(add, group)
    required = {p.atom for p in op.preconditions if p.atom.value is True}
    for e in op.effects:
        if e.value is not False or e.predicate in group or e.negate() not in required:
            continue
        if not keyed:
            yield (e.predicate, None)
            continue
        for j, t in enumerate(e.args):
            if key == (t,):
                yield (e.predicate, j)


def find_invariants(domain: Domain, max_size: int = 4, max_candidates: int = 2000) -> list[MutexGroup]:
    """Mutex groups that every operator preserves (not yet checked against an initial state)."""
    fluent = sorted(
        {e.predicate for o in domain.operators for e in o.effects}
        - set(domain.static_predicates)
    )
    queue: list[frozenset[Member]] = []
    for p in fluent:
        arity = domain.predicates[p].arity
        queue.append(frozenset({(p, None)}))
        queue.extend(frozenset({(p, i)}) for i in range(arity))
    seen: set[frozenset[Member]] = set(queue)
    valid: list[frozenset[Member]] = []
    while queue and len(seen) <= max_candidates:
        cand = queue.pop(0)
        group = dict(cand)
        if len(group) != len(cand):
            continue  # a predicate twice
        ok = True
        for op in domain.operators:
            good, unbalanced = _balanced(op, group)
            if good:
                continue
            ok = False
            if len(cand) < max_size:
                for add in unbalanced[:1]:
                    for ext in _extensions(op, group, add):
                        nxt = cand | {ext}
                        if nxt not in seen:
                            seen.add(nxt)
                            queue.append(nxt)
            break
        if ok:
            valid.append(cand)
    maximal = [g for g in valid if not any(g < h for h in valid)]
    groups = [MutexGroup(g) for g in sorted(maximal, key=lambda g: sorted(map(str, g)))]
    log.debug("domain %s: invariant candidates %d, groups %s", domain.name, len(seen),
              ", ".join(map(str, groups)))
    return groups


def initially_valid(group: MutexGroup, atoms: Iterable[Atom]) -> bool:
    """At most one member per key among ``atoms`` (the initial state)."""
    seen: set[tuple[Term, ...]] = set()
    for a in atoms:
        k = group.key_of(a)
        if k is None:
            continue
        if k in seen:
            return False
        seen.add(k)
    return True


def infer_mutexes(domain: Domain, init: object, max_size: int = 4) -> tuple[MutexGroup, ...]:
    """Invariant groups of ``domain`` that hold in ``init`` (a :class:`State` or atoms)."""
    atoms = list(init.atoms()) if isinstance(init, ListsFacts) else list(init)  # type: ignore[call-overload]
    out = []
    for g in find_invariants(domain, max_size):
        # a group whose members are never true and never added is useless
        if initially_valid(g, atoms):
            out.append(g)
        else:
            log.debug("mutex group %s does not hold initially; dropped", g)
    return tuple(out)


# --------------------------------------------------------------------------- conflict rule


class MutexRule:
    """A :data:`nowplan.core.atoms.ConflictRule`: two different true members with one key."""

    __slots__ = ("groups", "_index")

    def __init__(self, groups: Sequence[MutexGroup]) -> None:
        self.groups = tuple(groups)
        index: dict[str, list[tuple[int, int | None]]] = {}
        for gi, g in enumerate(self.groups):
            for pred, pos in g.members:
                index.setdefault(pred, []).append((gi, pos))
        self._index = {p: tuple(v) for p, v in index.items()}

    def __call__(self, a: Atom, b: Atom) -> bool:
        ia = self._index.get(a.predicate)
        if ia is None:
            return False
        ib = self._index.get(b.predicate)
        if ib is None or a.value is not True or b.value is not True:
            return False
        for ga, pa in ia:
            for gb, pb in ib:
                if ga == gb and (pa is None or a.args[pa] == b.args[pb]):  # type: ignore[index]
                    return a.args != b.args or a.predicate != b.predicate
        return False

    def group_keys(self, a: Atom) -> list[tuple[int, object]]:
        """Keys under which at most one true atom may hold (for linear-time checks)."""
        if a.value is not True:
            return []
        return [(gi, a.args[pos] if pos is not None else None) for gi, pos in self._index.get(a.predicate, ())]

    def __repr__(self) -> str:
        return "MutexRule(" + ", ".join(map(str, self.groups)) + ")"


def mutex_rule(groups: Sequence[MutexGroup]) -> MutexRule:
    return MutexRule(groups)
