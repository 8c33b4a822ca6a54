"""Pre-images of a long action sequence with incremental conflict checks.

:func:`nowplan.planning.preimage.regress_through` checks every pre-image
for conflicts from scratch: each step's keyed check (at most one true atom
per mutex group) reads the group keys of every atom of the goal, so a plan
of n steps regressed from a goal of m atoms costs O(n·m) key computations
(a visit-all plan of 1,152 steps over 900 cells: ~10^6 calls, half the
process's time under cProfile).  Here the group keys of the current goal
are kept in a map from group key to atom and updated by each step's removed
and added atoms, so a step costs what its action touches, plus building the
new goal's frozenset.  The result is the same: a clash among the atoms a
step checks involves a removed or added atom, because the goal it starts
from is free of clashes (the first one is checked in full).

Only for domains whose conflict rules are all keyed (the mutex groups of
PDDL domains); otherwise, or when the goal itself clashes,
:func:`regress_through` answers.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from nowplan.core.atoms import Atom, Goal, KeyedRule, contradiction
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.preimage import regress_through


def regress_chain(goal: Goal, actions: Sequence[Action], levels: LevelMap, domain: Domain,
                  drop: frozenset[str]) -> tuple[list[Goal], int | None]:
    """What :func:`regress_through` returns: ``([g0, …, gn = goal], None)``, or the goals regressed so far
    and the index of the action that fails."""
    rules = domain.rules
    keyed = [c for c in rules.conflicts if isinstance(c, KeyedRule)]
    if len(keyed) != len(rules.conflicts) or contradiction(list(goal.atoms), rules) is not None:
        return regress_through(goal, actions, levels, domain, drop)

    def keys(a: Atom) -> list[Any]:
        return [k for rule in keyed for k in rule.group_keys(a)]

    table = goal.by_key()  # fluent -> atom of the current goal
    owner: dict[Any, Atom] = {}  # group key -> the current goal's atom in that group (at most one)
    for a in table.values():
        for k in keys(a):
            owner[k] = a

    def drop_atom(a: Atom) -> None:
        del table[a.key]
        for k in keys(a):
            if owner.get(k) == a:
                del owner[k]

    goals = [goal]
    for i in range(len(actions) - 1, -1, -1):
        act = actions[i]
        effects = {e.key: e for e in act.effects()}
        removed: list[Atom] = []
        for key, e in effects.items():
            hit = table.get(key)
            if hit is None:
                continue
            if not rules.rule(hit.predicate).entails(e.value, hit.value):
                goals.reverse()
                return goals, i
            removed.append(hit)
        if keyed and len(table) > len(removed):  # preimage's check: after the action its effects hold
            gone = set(removed)
            seen: dict[Any, Atom] = {}
            for e in effects.values():
                for k in keys(e):
                    other: Atom | None = seen.get(k)
                    if other is None:
                        other = owner.get(k)
                        if other is not None and other in gone:
                            other = None
                    if other is not None and other != e:
                        goals.reverse()
                        return goals, i
                    seen[k] = e
        for a in removed:
            drop_atom(a)
        # conjoin the kept preconditions: merged per fluent, then the keyed check of the added atoms
        added: list[Atom] = []
        for p in act.preconditions(levels.level(act)):
            if p.predicate in drop:
                continue
            old = table.get(p.key)
            if old is None:
                table[p.key] = p
                added.append(p)
                continue
            rule = rules.rule(p.predicate)
            if not rule.compatible(old.value, p.value):
                goals.reverse()
                return goals, i
            merged = Atom(p.predicate, p.args, rule.meet(old.value, p.value))
            if merged != old:
                drop_atom(old)
                table[p.key] = merged
                added.append(merged)
        if keyed:
            for a in added:
                if table.get(a.key) is not a:
                    continue  # merged again by a later precondition of the same fluent
                for k in keys(a):
                    other = owner.get(k)
                    if other is not None and other != a:
                        goals.reverse()
                        return goals, i
                    owner[k] = a
        goals.append(Goal(frozenset(table.values())))
    goals.reverse()
    return goals, None
