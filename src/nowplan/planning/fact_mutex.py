"""Mutual exclusion of ground facts, from the domain's conflict rules (inferred invariants).

:class:`FactMutex` answers ``mutex(f, g)`` over fact ids (landmark orders, the forward task);
:class:`Excluder` lists the reached atoms an added atom excludes (the task's delete rows).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from nowplan.core.atoms import Atom, KeyedRule
from nowplan.core.domain import Domain


class FactMutex:
    """``mutex(f, g)``: the conflict rules (inferred invariants) exclude facts ``f`` and ``g`` together."""

    def __init__(self, facts: list[Atom], keyed: list[KeyedRule]) -> None:
        self._facts = facts
        self._keyed = keyed
        self._memo: dict[int, frozenset[Any]] = {}

    def keys(self, f: int) -> frozenset[Any]:
        """The (rule, group) pairs of fact ``f``: two facts sharing one are mutex."""
        hit = self._memo.get(f)
        if hit is None:
            a = self._facts[f]
            hit = self._memo[f] = frozenset((i, k) for i, r in enumerate(self._keyed) for k in r.group_keys(a)) \
                if a.value is True else frozenset()
        return hit

    def isolated(self, f: int) -> bool:
        """No fact is mutex with ``f`` (it is in no group)."""
        return not self.keys(f)

    def __call__(self, f: int, g: int) -> bool:
        return f != g and bool(self.keys(f) & self.keys(g))


class Excluder:
    """The reached atoms that the domain's conflict rules exclude once an atom is added."""

    def __init__(self, domain: Domain, reached: Iterable[Atom]) -> None:
        self.rules = domain.rules
        self.reached = sorted(reached)
        self.memo: dict[Atom, frozenset[Atom]] = {}
        keyed = [c for c in self.rules.conflicts if isinstance(c, KeyedRule)]
        self.plain = [c for c in self.rules.conflicts if not isinstance(c, KeyedRule)]
        self.groups: dict[Any, list[Atom]] = {}
        self.keyed = keyed
        self._reached = frozenset(self.reached)
        self._keys: dict[Atom, tuple[Any, ...]] = {}
        for a in self.reached:
            for rule in keyed:
                for k in rule.group_keys(a):
                    self.groups.setdefault(k, []).append(a)

    def __call__(self, adds: Iterable[Atom]) -> set[Atom]:
        out: set[Atom] = set()
        for e in adds:
            hit = self.memo.get(e)
            if hit is None:
                found: set[Atom] = set()
                for rule in self.keyed:
                    for k in rule.group_keys(e):
                        found.update(x for x in self.groups.get(k, ()) if x != e)
                if self.plain:  # what contradiction([e, x], new=[x]) adds to the keyed groups above
                    found.update(x for x in self.reached if x != e and self._plain_clash(e, x))
                hit = self.memo[e] = frozenset(found)
            out |= hit
        return out

    def _plain_clash(self, e: Atom, x: Atom) -> bool:
        """``x`` and ``e`` cannot hold together by the value rule of their fluent or a plain rule
        (``contradiction``'s pairwise part; the keyed rules' pairs come from the groups, without
        asking every rule's keys of both atoms per pair: 97,627 pairs on the held-out tidy house
        took 2.3 s of a 5.3 s HPN run that way)."""
        if x.key == e.key:
            return not self.rules.rule(x.predicate).compatible(x.value, e.value)
        return any(c(x, e) or c(e, x) for c in self.plain)

    def keys(self, a: Atom) -> tuple[Any, ...]:
        """The group keys of ``a`` under the keyed rules (two true atoms sharing one exclude each other)."""
        hit = self._keys.get(a)
        if hit is None:
            hit = self._keys[a] = tuple(k for rule in self.keyed for k in rule.group_keys(a))
        return hit

    def beyond(self, e: Atom, held: list[Atom]) -> list[Atom] | None:
        """The reached atoms ``e`` excludes that no atom of ``held`` (true atoms) excludes: ``self([e])``
        minus ``self(held)``, found without making either set; None where plain (unkeyed) rules exist.

        An atom shares a group with ``e``; it is kept only if every group it is in holds no atom of
        ``held`` but itself.  A group of ``e`` that an atom of ``held`` is in leaves only that atom (the
        rest it excludes already), so only the groups ``held`` leaves alone are walked (a task's abstract
        rows: ``in(p, t)`` added by a load whose kept precondition ``at(p, l)`` is in the same group)."""
        if self.plain:
            return None
        by_key: dict[Any, list[Atom]] = {}
        for c in held:
            for k in self.keys(c):
                by_key.setdefault(k, []).append(c)
        out: list[Atom] = []
        seen: set[Atom] = set()
        for k in self.keys(e):
            holders = by_key.get(k)
            for x in (holders if holders is not None else self.groups.get(k, ())):
                if x == e or x in seen or (holders is not None and x not in self._reached):
                    continue
                seen.add(x)
                if all(all(h == x for h in by_key.get(k2, ())) for k2 in self.keys(x)):
                    out.append(x)
        return out
