"""Pre-images over fact ids: what :func:`nowplan.planning.preimage.preimage` computes, per node.

A subgoal is a frozenset of fact ids (:class:`~nowplan.core.facts.FactTable`).
When the search expands a node it indexes the node once (:class:`NodeIndex`:
its facts by fluent and by conflict key); each successor then costs a few
lookups per effect and precondition of the action (:class:`ActionFacts`,
kept on the action):

1. the node's facts of the fluents the effects set are removed if an effect
   entails them, else the regression fails;
2. one mutex pass: an effect that shares a conflict key with a remaining
   fact fails it (and two effects that share one);
3. the kept preconditions are merged per fluent as ``conjoin`` does, and a
   precondition that shares a key with a remaining fact, or with another
   precondition, fails it.

Pairs of remaining facts are not checked again: every node the search
generates was checked whole when it was made, so only a root goal can be
contradictory, and the search regresses a contradictory root with the
Goal-level :func:`~nowplan.planning.preimage.preimage` instead
(:meth:`FactTable.consistent` decides).  Plain pairwise conflict rules are
asked once per pair of facts, and the table keeps per fact the facts it was
checked against and those it conflicts with, so a successor's check is a few
set operations (:meth:`FactTable.plain_clash`; on a held-out domain with plain
rules the pairwise calls were half of ``regress``'s time).
"""

from __future__ import annotations

from collections.abc import Hashable
from typing import TYPE_CHECKING

from nowplan.core.atoms import Goal
from nowplan.core.facts import FactTable
from nowplan.core.operators import Action

if TYPE_CHECKING:
    from nowplan.planning.ground_task import GroundTask


class ActionFacts:
    """An action's effects and kept preconditions as fact ids, at one level."""

    __slots__ = ("all_effs", "effs", "eff_fl", "eff_keys", "self_clash", "pre")

    def __init__(self, table: FactTable, act: Action, level: int | None, drop: frozenset[str]) -> None:
        self._set(table, tuple(table.id(e) for e in act.effects()),
                  tuple(table.id(p) for p in act.preconditions(level) if p.predicate not in drop))

    @classmethod
    def of_ids(cls, table: FactTable, effects: tuple[int, ...], pre: tuple[int, ...]) -> ActionFacts:
        """From the effects' and the kept preconditions' ids (a ground task's, in the operator's order)."""
        info = cls.__new__(cls)
        info._set(table, effects, pre)
        return info

    def _set(self, table: FactTable, effects: tuple[int, ...], pre: tuple[int, ...]) -> None:
        by_fluent: dict[int, int] = {}
        self.all_effs = effects
        for f in self.all_effs:
            by_fluent[table.fluent[f]] = f  # a later effect on one fluent wins, as in a dict by key
        self.effs = tuple(by_fluent.values())
        self.eff_fl = tuple(by_fluent.items())
        keys: list[tuple[Hashable, int]] = []
        seen: dict[Hashable, int] = {}
        clash = False
        for f in self.effs:
            for k in table.gkeys[f]:
                o = seen.get(k)
                if o is not None and o != f:
                    clash = True
                seen[k] = f
                keys.append((k, f))
        self.eff_keys = tuple(keys)
        self.self_clash = clash
        self.pre = pre


def action_facts(
    table: FactTable, act: Action, level: int | None, drop: frozenset[str], task: GroundTask | None = None
) -> ActionFacts:
    """``act``'s facts at ``level`` (kept on the action); read off ``task`` (built with ``drop``) when it holds ``act``."""
    key = (table, level, drop)
    info: ActionFacts | None = act.memo.get(key)
    if info is None:
        k = task.index.get(act.key) if task is not None and task.drop == drop else None
        if k is not None and task is not None and task.operators[task.op[k]] is act.operator:
            pre = tuple([f for f, c, _ in task.pre[k] if level is None or c > level])
            info = ActionFacts.of_ids(table, task.effects[k], pre)
        else:
            info = ActionFacts(table, act, level, drop)
        act.memo[key] = info
    return info


class NodeIndex:
    """A subgoal's facts by fluent and by conflict key (built once per expanded node)."""

    __slots__ = ("fs", "by_fluent", "by_key")

    def __init__(self, table: FactTable, fs: frozenset[int]) -> None:
        self.fs = fs
        fl = table.fluent
        gk = table.gkeys
        self.by_fluent = dict(zip(map(fl.__getitem__, fs), fs))
        self.by_key: dict[Hashable, int] = {k: f for f in fs for k in gk[f]} if table.keyed else {}


def regress(table: FactTable, node: NodeIndex, info: ActionFacts) -> frozenset[int] | None:
    """The pre-image of a consistent subgoal through an action, or ``None`` (see the module docstring)."""
    fs = node.fs
    nf = node.by_fluent
    removed: set[int] = set()
    for flu, e in info.eff_fl:
        o = nf.get(flu)
        if o is not None:
            if o != e and not table.entails(e, o):
                return None
            removed.add(o)
    conflicts = table.has_conflicts
    if conflicts and len(fs) > len(removed):
        if info.self_clash:
            return None
        nk = node.by_key
        for k, e in info.eff_keys:
            o = nk.get(k)
            if o is not None and o != e and o not in removed:
                return None
        if table.plain:
            for e in info.effs:
                if table.plain_clash(e, fs, removed):
                    return None
    if not info.pre:
        return fs.difference(removed) if removed else fs
    fl = table.fluent
    new: dict[int, int] = {}  # fluent -> fact, for facts not already in the subgoal
    for p in info.pre:
        flu = fl[p]
        cur = new.get(flu)
        if cur is None:
            old = nf.get(flu)
            if old is None or old in removed:
                new[flu] = p
                continue
            if old == p:
                continue
            m = table.meet(old, p)
            if m is None:
                return None
            if m != old:
                removed.add(old)  # replaced by the merged fact
                new[flu] = m
        elif cur != p:
            m = table.meet(cur, p)
            if m is None:
                return None
            new[flu] = m
    if not new:
        return fs.difference(removed) if removed else fs
    if conflicts:
        nk = node.by_key
        gk = table.gkeys
        local: dict[Hashable, int] = {}
        for n in new.values():
            for k in gk[n]:
                x = nk.get(k)
                if x is not None and x != n and x not in removed:
                    return None
                x = local.get(k)
                if x is not None and x != n:
                    return None
                local[k] = n
        if table.plain:
            news = list(new.values())
            for i, n in enumerate(news):
                if table.plain_clash(n, fs, removed):
                    return None
                for b in news[i + 1 :]:
                    if table.plain_conflict(n, b):
                        return None
    return (fs.difference(removed) if removed else fs).union(new.values())


class GoalOf:
    """A node's subgoal as a :class:`Goal`, made on the first call (for generators)."""

    __slots__ = ("table", "fs", "goal")

    def __init__(self, table: FactTable, fs: frozenset[int]) -> None:
        self.table = table
        self.fs = fs
        self.goal: Goal | None = None

    def __call__(self) -> Goal:
        if self.goal is None:
            self.goal = self.table.goal(self.fs)
        return self.goal

