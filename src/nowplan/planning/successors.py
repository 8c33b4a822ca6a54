"""A regression call's successor templates: the achievers of a fact with their facts at their level and cost.

The search asks, for each fact of a node it expands, which actions achieve it
(:meth:`Grounder.achievers`) and, per action, its effects and kept preconditions
as fact ids at the action's level (:class:`~nowplan.planning.subgoals.ActionFacts`)
and its cost.  :class:`Successors` answers per call and keeps the answers:

* per achiever list within the call (the grounder keeps one list per atom, or per
  atom and what generators read of the goal; the lists are held, so their ids stay
  theirs);
* across the calls of one problem, where every call gets the same achievers (no
  generator achieves the atom's predicate) and every cost is a number: by fact id
  in the ground task, with the facts at the top level; a call whose level map puts
  one of the actions at another level redoes only that entry.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.facts import FactTable
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.ground_task import GroundTask
from nowplan.planning.grounding import Grounder
from nowplan.planning.subgoals import ActionFacts, action_facts

Template = tuple[Action, ActionFacts, float]


class Successors:
    """The successor templates of one planner call (see the module docstring)."""

    def __init__(self, table: FactTable, grounder: Grounder, levels: LevelMap, drop: frozenset[str],
                 cost: Callable[[Action], float]) -> None:
        self.table = table
        self.grounder = grounder
        self.levels = levels
        self.drop = drop
        self.cost = cost
        self.task: GroundTask | None = None  # the problem's ground task, where the search built one
        self._over_keys = frozenset(k for k, lv in levels.overrides if lv != levels.top)
        self._over_ops = frozenset(n for n, lv in levels.floors if lv < levels.top)  # operators with a floor
        self._by_fact: dict[int, list[Template]] = {}  # this call's templates by fact id
        self._templates: dict[int, tuple[list[Action], list[Template]]] = {}
        self._shared_store: Any = False  # not looked up yet (see _shared)

    def __call__(self, target: int, goal_of: Callable[[], Goal]) -> list[Template]:
        """The achievers of fact ``target`` with their facts at their level and their cost."""
        local = self._by_fact.get(target)
        if local is not None:
            return local
        shared = self._shared
        atom = self.table.atoms[target]
        if shared is not None and self.grounder.shares_answer(atom):
            hit = shared.get(target)
            if hit is None:
                acts = self.grounder.achievers(atom, goal_of)
                T, top, drop, task = self.table, self.levels.top, self.drop, self.task
                hit = shared[target] = [(act, action_facts(T, act, top, drop, task), self.cost(act)) for act in acts]
            out = hit
            over, ops = self._over_keys, self._over_ops
            if (over or ops) and any(e[0].key in over or e[0].key[0] in ops for e in out):
                T, levels, drop, task = self.table, self.levels, self.drop, self.task
                out = [(a, action_facts(T, a, levels.level(a), drop, task), c)
                       if a.key in over or a.key[0] in ops else (a, i, c) for a, i, c in out]
            self._by_fact[target] = out
            return out
        acts = self.grounder.achievers(atom, goal_of)
        kept = self._templates.get(id(acts))
        if kept is not None and kept[0] is acts:
            return kept[1]
        levels, drop, T, task = self.levels, self.drop, self.table, self.task
        out = [(act, action_facts(T, act, levels.level(act), drop, task), self.cost(act)) for act in acts]
        if self.grounder.kept:
            self._templates[id(acts)] = (acts, out)
        return out

    @property
    def shares(self) -> bool:
        """The templates come from the problem's shared store (numeric costs; see the module docstring)."""
        return self._shared is not None

    @property
    def overridden(self) -> bool:
        """The level map puts some actions at other levels than its top (their templates differ)."""
        return bool(self._over_keys or self._over_ops)

    @property
    def uniform(self) -> bool:
        """Every fact's templates are the problem's shared ones, at the top level (no level overrides)."""
        return self._shared is not None and not self._over_keys and not self._over_ops

    @property
    def _shared(self) -> dict[int, list[Template]] | None:
        """The templates kept in the ground task for this call's top level (numeric costs only)."""
        if self._shared_store is False:
            task = self.task
            store: Any = None
            if task is not None and task.all_fixed and task.drop == self.drop:
                key = ("successor templates", self.levels.top)
                store = task.memo.get(key)
                if not isinstance(store, dict):
                    store = task.memo[key] = {}
            self._shared_store = store
        return self._shared_store  # type: ignore[no-any-return]
