"""A problem's ground actions as fact ids, built in bulk from the operator schemas.

Every planner call of the executive on one problem (same objects, same static
facts) asks for the same ground task: the h_add of the regression search
(:mod:`nowplan.planning.hadd_relevant`) explores it, and the search takes the
achievers of a fact from it.  It is built once per (domain, objects, static
facts, dropped statics) and kept in the domain's fact table.

The build does not bind an :class:`~nowplan.core.atoms.Atom` per precondition
and effect: per operator, each precondition and effect becomes a *template*
(its predicate, the parameter position or constant of each argument, its
value); an instance's argument tuple then gives each fact's key
``(predicate, args, value)`` and the table's id for it in one dictionary
lookup (:meth:`FactTable.id_of`; an atom is made only for a fact the table has
not seen).  The instances are those of :meth:`Grounder._fill` (static joins
against the listed facts, then typed objects), in its order; :class:`Action`
objects are made on demand, one per instance of the domain
(``FactTable.actions``).  ``tests/test_ground_task.py`` checks the task against
instantiating and binding every action.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass
from operator import itemgetter
from typing import Any

from nowplan.core.atoms import Atom, Term, Var
from nowplan.core.facts import FactTable
from nowplan.core.operators import Action, Operator

_Args = tuple[Term, ...]


@dataclass(frozen=True)
class GroundAction:
    """A ground action with its preconditions (statics left out) and effects as atoms."""

    action: Action
    pre: tuple[tuple[Atom, int], ...]  # (atom, criticality), statics left out
    effects: tuple[Atom, ...]


def _args_maker(args: Sequence[Term], pos: dict[Var, int]) -> Callable[[_Args], _Args]:
    """A function from an instance's arguments to a template's ground arguments."""
    idx = [pos.get(a, -1) if isinstance(a, Var) else -1 for a in args]
    if all(i >= 0 for i in idx):
        if len(idx) >= 2:
            get = itemgetter(*idx)
            return lambda xs: tuple(get(xs))
        if len(idx) == 1:
            j = idx[0]
            return lambda xs: (xs[j],)
        return lambda xs: ()
    consts = list(args)
    spec = [(i, consts[n]) for n, i in enumerate(idx)]
    return lambda xs: tuple(xs[i] if i >= 0 else c for i, c in spec)


def _value_maker(value: Any, pos: dict[Var, int]) -> Callable[[_Args], Any]:
    if isinstance(value, Var) and value in pos:
        j = pos[value]
        return lambda xs: xs[j]
    return lambda xs: value


class GroundTask:
    """The ground actions of a problem as fact ids (see the module docstring).

    Per action ``k``: ``pre[k]`` its (fact, criticality, positive twin or -1)
    preconditions without the dropped statics, ``effects[k]`` its effects' facts,
    ``fixed_cost[k]`` its cost (``None`` when it reads the belief); ``op[k]`` and
    ``args[k]`` name the instance.
    """

    def __init__(self, table: FactTable, operators: Sequence[Operator], fills: Sequence[tuple[int, list[_Args]]],
                 drop: frozenset[str]) -> None:
        self.table = table
        self.drop = drop
        self.operators = tuple(operators)
        self.op: list[int] = []
        self.args: list[_Args] = []
        self.pre: list[tuple[tuple[int, int, int], ...]] = []  # (fact, criticality, positive twin or -1)
        self.effects: list[tuple[int, ...]] = []
        self.fixed_cost: list[float | None] = []
        id_of = table.id_of
        for i, args_list in fills:
            op = self.operators[i]
            pos = {v: j for j, v in enumerate(op.params)}
            pres = [(p.atom.predicate, _args_maker(p.atom.args, pos), _value_maker(p.atom.value, pos), p.criticality)
                    for p in op.preconditions if p.atom.predicate not in drop]
            effs = [(e.predicate, _args_maker(e.args, pos), _value_maker(e.value, pos)) for e in op.effects]
            c = op.cost
            fixed = None if callable(c) else float(c)
            for xs in args_list:
                pre = []
                for pred, mk, val, crit in pres:
                    a, v = mk(xs), val(xs)
                    pre.append((id_of(pred, a, v), crit, id_of(pred, a, True) if v is False else -1))
                self.pre.append(tuple(pre))
                self.effects.append(tuple([id_of(pred, mk(xs), val(xs)) for pred, mk, val in effs]))
                self.op.append(i)
                self.args.append(xs)
                self.fixed_cost.append(fixed)
        self.n = len(self.op)
        self.all_fixed = all(c is not None for c in self.fixed_cost)
        names = [op.name for op in self.operators]
        self.index = {(names[i], xs): k for k, (i, xs) in enumerate(zip(self.op, self.args, strict=True))}
        self._kept: dict[int, tuple[list[tuple[tuple[int, int], ...]], dict[int, list[int]]]] = {}
        self._adders: dict[int, list[int]] | None = None
        self._acts: tuple[GroundAction, ...] | None = None
        self.memo: dict[Hashable, object] = {}  # what explorations keep between calls (hadd_relevant)

    def action(self, k: int) -> Action:
        """Action ``k``, one object per instance of the domain (shared with the grounder)."""
        key = (self.op[k], self.args[k])
        act = self.table.actions.get(key)
        if act is None:
            act = self.table.actions[key] = Action(self.operators[self.op[k]], self.args[k])
        return act

    @property
    def acts(self) -> tuple[GroundAction, ...]:
        """Every action with its atoms (made on first use: for tests and the reference exploration)."""
        if self._acts is None:
            atoms = self.table.atoms
            self._acts = tuple(
                GroundAction(self.action(k), tuple((atoms[f], c) for f, c, _ in self.pre[k]),
                             tuple(atoms[e] for e in self.effects[k]))
                for k in range(self.n)
            )
        return self._acts

    def adders(self) -> dict[int, list[int]]:
        """Per fact id the actions (ascending) that add it."""
        if self._adders is None:
            self._adders = {}
            for k, effs in enumerate(self.effects):
                for e in effs:
                    self._adders.setdefault(e, []).append(k)
        return self._adders

    def kept(self, level: int) -> tuple[list[tuple[tuple[int, int], ...]], dict[int, list[int]]]:
        """Per action the (fact, twin) preconditions kept at ``level``; per fact the actions waiting for it."""
        hit = self._kept.get(level)
        if hit is None:
            kept = [tuple((f, t) for f, c, t in pre if c > level) for pre in self.pre]
            waiting: dict[int, list[int]] = {}
            for k, pre in enumerate(kept):
                for f, _ in pre:
                    waiting.setdefault(f, []).append(k)
            hit = self._kept[level] = (kept, waiting)
        return hit
