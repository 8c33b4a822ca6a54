"""Conjunction and regression of goals at the cost of what a step touches, not of the goal's size.

A goal carries two indexes, made once and then handed on: its atoms by fluent (``Goal.get``'s) and,
for the keyed conflict rules of the domain (at most one true atom per group key), the atom that holds
each group key.  :func:`conjoin` and :func:`regress_step` (what ``preimage`` computes) check only the
pairs that involve an added atom, against those indexes, and give the goal they make its indexes
derived by copying the parent's (a copy in C) and applying the step's few changes.  The answers are
those of a check of the whole goal: a goal is free of clashes when it was made (by ``Goal.of``, by
``conjoin``, or by a regression of one), so a clash after a step involves an atom the step adds; a goal
whose group index finds a clash within itself (one built directly from atoms) is checked in full.

Before this, every pre-image and conjunction read the group keys of every atom of the goal: gripper
with 250 balls under ``--criticality auto`` (goals of ~250 atoms regressed at each of ~1,000 steps) spent
2.2 s of a 7.7 s profile in ``preimage``.  ``planning/preimage_chain.py`` keeps the same indexes along
one action sequence.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from nowplan.core.atoms import Atom, ConflictRule, Goal, Rules, Term, _keyed, contradiction, group_keys_of

Table = dict[tuple[str, tuple[Term, ...]], Atom]
Groups = dict[Any, Atom]


def table_of(goal: Goal) -> Table:
    """The goal's atoms by fluent (shared: not to be changed)."""
    table: Table | None = goal.__dict__.get("_by_key")
    if table is None:
        table = goal.by_key()
        object.__setattr__(goal, "_by_key", table)
    return table


def groups_of(goal: Goal, rules: Rules) -> Groups | None:
    """Group key -> the goal's atom in that group, under ``rules``' keyed conflict rules; ``None`` when
    the goal itself has two atoms in one group (then the callers check in full).  Shared: not to be
    changed."""
    hit = goal.__dict__.get("_groups")
    if hit is not None and hit[0] is rules.conflicts:
        return hit[1]  # type: ignore[no-any-return]
    keyed, _, memo = _keyed(rules)
    groups: Groups = {}
    clash = False
    for a in goal.atoms:
        for k in group_keys_of(a, keyed, memo):
            other = groups.get(k)
            if other is not None and other != a:
                clash = True
            groups[k] = a
        if clash:
            break
    out = None if clash else groups
    object.__setattr__(goal, "_groups", (rules.conflicts, out))
    return out


def _made(atoms: Table, rules: Rules, groups: Groups | None) -> Goal:
    g = Goal(frozenset(atoms.values()))
    object.__setattr__(g, "_by_key", atoms)
    if groups is not None:
        object.__setattr__(g, "_groups", (rules.conflicts, groups))
    return g


def _plain_clash(new: list[Atom], atoms: Iterable[Atom], rules: Rules, plain: list[ConflictRule]) -> bool:
    """A pair (a new atom, any atom) that a pairwise rule or an incompatible value rules out."""
    every = list(atoms)
    for a in new:
        for b in every:
            if a == b:
                continue
            if a.key == b.key:
                if not rules.rule(a.predicate).compatible(a.value, b.value):
                    return True
            elif any(c(a, b) or c(b, a) for c in plain):
                return True
    return False


def conjoin(goal: Goal, extra: Iterable[Atom], rules: Rules) -> Goal | None:
    """``goal ∧ extra`` simplified per fluent, or ``None`` if contradictory (``atoms.conjoin``)."""
    if not rules.conflicts:
        return _conjoin(dict(table_of(goal)), None, list(extra), rules, False)
    keyed, _, _ = _keyed(rules)
    parent = groups_of(goal, rules) if keyed else None
    if keyed and parent is None:  # a goal with a clash of its own: the whole check
        return _conjoin(dict(table_of(goal)), None, list(extra), rules, True)
    return _conjoin(dict(table_of(goal)), None if parent is None else dict(parent), list(extra), rules, False)


def _conjoin(table: Table, groups: Groups | None, extra: list[Atom], rules: Rules, full: bool) -> Goal | None:
    """Conjoin ``extra`` into ``table`` and ``groups`` (a goal's indexes, owned: changed in place); with
    ``full`` (the goal clashes by itself), the keyed rules are checked over every atom."""
    base_of = {a.key: table.get(a.key) for a in extra}
    for a in extra:
        old = table.get(a.key)
        if old is None:
            table[a.key] = a
            continue
        rule = rules.rule(a.predicate)
        if not rule.compatible(old.value, a.value):
            return None
        merged = Atom(a.predicate, a.args, rule.meet(old.value, a.value))
        if merged != old:
            table[a.key] = merged
    if not rules.conflicts:
        return _made(table, rules, None)
    keyed, plain, memo = _keyed(rules)
    new = [table[k] for k in base_of]
    if full:
        if contradiction(list(table.values()), rules, new=new) is not None:
            return None
        groups = None
    elif groups is not None:
        for old in base_of.values():  # an atom of the goal that a merge replaced leaves its groups
            if old is not None and table[old.key] != old:
                for k in group_keys_of(old, keyed, memo):
                    if groups.get(k) == old:
                        del groups[k]
        for x in new:
            for k in group_keys_of(x, keyed, memo):
                other = groups.get(k)
                if other is not None and other != x and table.get(other.key) == other:
                    return None
                groups[k] = x
    if plain and _plain_clash(new, table.values(), rules, plain):
        return None
    return _made(table, rules, groups)


def regress_step(goal: Goal, effects: dict[tuple[str, tuple[Term, ...]], Atom], pre: list[Atom],
                 rules: Rules) -> Goal | None:
    """The pre-image of ``goal`` through an action with these effects (by fluent) and kept
    preconditions: ``None`` if an effect destroys a goal atom or excludes one that stays (as
    ``planning.preimage.preimage``)."""
    table = table_of(goal)
    removed: list[Atom] = []
    for key, e in effects.items():
        a = table.get(key)
        if a is not None:
            if not rules.rule(a.predicate).entails(e.value, a.value):
                return None
            removed.append(a)
    keyed, plain, memo = _keyed(rules)
    parent = groups_of(goal, rules) if keyed else None
    if rules.conflicts and len(table) > len(removed):
        # after the action its effects hold: a remaining atom they exclude can never come true
        effs = list(effects.values())
        gone = set(removed)
        if keyed:
            if parent is None:
                rest = [a for a in goal.atoms if a not in gone]
                if contradiction(effs + rest, rules, new=effs) is not None:
                    return None
            else:
                seen: Groups = {}
                for e in effs:
                    for k in group_keys_of(e, keyed, memo):
                        other = seen.get(k)
                        if other is None:
                            other = parent.get(k)
                            if other is not None and other in gone:
                                other = None
                        if other is not None and other != e:
                            return None
                        seen[k] = e
        if plain and _plain_clash(effs, effs + [a for a in goal.atoms if a not in gone], rules, plain):
            return None
    rest_table = dict(table)
    for a in removed:
        del rest_table[a.key]
    rest_groups: Groups | None = None
    if parent is not None:
        rest_groups = dict(parent)
        for a in removed:
            for k in group_keys_of(a, keyed, memo):
                if rest_groups.get(k) == a:
                    del rest_groups[k]
    return _conjoin(rest_table, rest_groups, pre, rules, bool(keyed) and parent is None)
