"""Atoms interned as integers (fact ids), for searches that hash and compare many subgoals.

A :class:`FactTable` belongs to one domain (``Domain.facts``) and lives as long
as it: an atom gets its id the first time it is seen and keeps it, so a
ground action can keep its effects' and preconditions' ids between planner
calls.  Per fact the table keeps what regression asks at every node:

* the *fluent* id (predicate and arguments: one fact per value);
* whether the predicate's value rule is plain equality (then a fact entails
  another of its fluent only if it is the same fact);
* its keys under the domain's *keyed* conflict rules (``group_keys``: at
  most one true atom per key), computed once, so a subgoal's mutex check is
  a dictionary lookup per key;
* its sort key (predicate, arguments): the order in which a search visits a
  subgoal's atoms, the same as sorting the atoms (a goal has one atom per
  fluent).

Conflict rules without ``group_keys`` (plain pairwise callables) are asked
once per pair of facts and the answer is kept.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from typing import TYPE_CHECKING, Any
from nowplan.core.atoms import EQUALITY, Atom, Goal, KeyedRule, Rules, Term

if TYPE_CHECKING:
    from nowplan.core.operators import Action

FluentKey = tuple[str, tuple[Term, ...]]


class FactTable:
    """Interned atoms of one domain (see the module docstring)."""

    def __init__(self, rules: Rules) -> None:
        self.rules = rules
        self.keyed = tuple(c for c in rules.conflicts if isinstance(c, KeyedRule))
        self.plain = tuple(c for c in rules.conflicts if not isinstance(c, KeyedRule))
        self.has_conflicts = bool(self.keyed or self.plain)
        self.ids: dict[Atom, int] = {}
        self.by_key: dict[tuple[str, tuple[Term, ...], Any], int] = {}  # (predicate, args, value) -> id
        self.atoms: list[Atom] = []
        self.fluent: list[int] = []
        self.fluent_ids: dict[FluentKey, int] = {}
        self.equality: list[bool] = []  # the predicate's value rule is equality
        self._equality: dict[str, bool] = {}  # the same per predicate
        self.gkeys: list[tuple[Hashable, ...]] = []
        self.sort_key: list[tuple[str, tuple[Term, ...]]] = []
        self._pairs: dict[tuple[int, int], bool] = {}
        # per fact: the facts its plain conflicts were asked against, and those it conflicts with
        self._checked: dict[int, set[int]] = {}
        self._clash: dict[int, set[int]] = {}
        # ground actions by (operator index, arguments): one object per instance, so what a
        # planner keeps on an action (its facts' ids) outlives one call
        self.actions: dict[tuple[int, tuple[Any, ...]], Action] = {}
        # grounding answers shared by the planner calls of one problem (planning.grounding)
        self.grounding: dict[Hashable, Any] = {}
        # tables derived from the domain alone (e.g. the grounder's effects per predicate)
        self.derived: dict[str, Any] = {}

    def __len__(self) -> int:
        return len(self.atoms)

    def id(self, a: Atom) -> int:
        f = self.ids.get(a)
        if f is None:
            f = self._add(a)
        return f

    def id_of(self, predicate: str, args: tuple[Term, ...], value: Any) -> int:
        """The id of ``Atom(predicate, args, value)``, without making the atom when it is known."""
        f = self.by_key.get((predicate, args, value))
        if f is None:
            f = self._add(Atom(predicate, args, value))  # by_key and ids know the same atoms
        return f

    def _add(self, a: Atom) -> int:
        f = len(self.atoms)
        self.ids[a] = f
        self.by_key[(a.predicate, a.args, a.value)] = f
        self.atoms.append(a)
        key = (a.predicate, a.args)
        fl = self.fluent_ids.get(key)
        if fl is None:
            fl = self.fluent_ids[key] = len(self.fluent_ids)
        self.fluent.append(fl)
        eq = self._equality.get(a.predicate)
        if eq is None:
            eq = self._equality[a.predicate] = self.rules.rule(a.predicate) is EQUALITY
        self.equality.append(eq)
        if self.keyed:
            keys: list[Hashable] = []
            for rule in self.keyed:
                keys.extend(rule.group_keys(a))
            self.gkeys.append(tuple(keys))
        else:
            self.gkeys.append(())
        self.sort_key.append(key)
        return f

    def ids_of(self, atoms: Iterable[Atom]) -> frozenset[int]:
        get = self.by_key.get  # a tuple key hashes in C (an atom's dataclass hash runs Python code)
        out = []
        for a in atoms:
            f = get((a.predicate, a.args, a.value))
            out.append(self.id(a) if f is None else f)
        return frozenset(out)

    def goal(self, fs: Iterable[int]) -> Goal:
        return Goal(frozenset(map(self.atoms.__getitem__, fs)))  # (map: no generator frame per fact)

    def sorted(self, fs: Iterable[int]) -> list[int]:
        """Fact ids in the order of their atoms (as ``sorted(goal.atoms)``)."""
        return sorted(fs, key=self.sort_key.__getitem__)

    # -- relations between facts -------------------------------------------
    def entails(self, have: int, want: int) -> bool:
        """Same fluent assumed: does ``have``'s value guarantee ``want``'s?"""
        if have == want:
            return True
        if self.equality[want]:
            return False
        a, b = self.atoms[have], self.atoms[want]
        return self.rules.rule(b.predicate).entails(a.value, b.value)

    def plain_conflict(self, x: int, y: int) -> bool:
        """Do the plain (pairwise) conflict rules exclude facts ``x`` and ``y`` together?"""
        key = (x, y) if x < y else (y, x)
        r = self._pairs.get(key)
        if r is None:
            a, b = self.atoms[x], self.atoms[y]
            r = self._pairs[key] = any(c(a, b) or c(b, a) for c in self.plain)
        return r

    def plain_clash(self, e: int, fs: frozenset[int], removed: set[int]) -> bool:
        """Does ``e`` plainly conflict with a fact of ``fs`` not in ``removed``?

        ``any(plain_conflict(r, e) for r in fs if r not in removed)``, with each pair asked
        once and kept per fact as sets, so that a search asking again (every successor of every
        node) does set operations instead of one call per pair.
        """
        chk = self._checked.get(e)
        if chk is None:
            chk = self._checked[e] = set()
            self._clash[e] = set()
        clash = self._clash[e]
        if not chk.issuperset(fs):
            for r in fs.difference(chk):
                if self.plain_conflict(r, e):
                    clash.add(r)
                chk.add(r)
        if clash.isdisjoint(fs):
            return False
        return not clash.intersection(fs).issubset(removed)

    def consistent(self, fs: Iterable[int]) -> bool:
        """No two facts of ``fs`` share a fluent with incompatible values or a conflict rule's key."""
        seen: dict[Hashable, int] = {}
        fl: dict[int, int] = {}
        lst = list(fs)
        for f in lst:
            o = fl.get(self.fluent[f])
            if o is not None and o != f:
                a, b = self.atoms[o], self.atoms[f]
                if not self.rules.rule(a.predicate).compatible(a.value, b.value):
                    return False
            fl[self.fluent[f]] = f
            for k in self.gkeys[f]:
                o = seen.get(k)
                if o is not None and o != f:
                    return False
                seen[k] = f
        if self.plain:
            for i, x in enumerate(lst):
                for y in lst[i + 1 :]:
                    if x != y and self.fluent[x] != self.fluent[y] and self.plain_conflict(x, y):
                        return False
        return True

    def meet(self, old: int, new: int) -> int | None:
        """The fact for both values of one fluent (``conjoin``'s merge), or ``None`` if incompatible."""
        if old == new:
            return old
        if self.equality[new]:
            return None
        a, b = self.atoms[old], self.atoms[new]
        rule = self.rules.rule(b.predicate)
        if not rule.compatible(a.value, b.value):
            return None
        return self.id(Atom(b.predicate, b.args, rule.meet(a.value, b.value)))
