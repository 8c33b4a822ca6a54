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
import itertools
from operator import itemgetter
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Term, Var
from nowplan.core.facts import FactTable
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action, Operator, StateFreeCost

if TYPE_CHECKING:
    from nowplan.planning.grounding import Grounder

_Args = tuple[Term, ...]


@dataclass(frozen=True)
class GroundAction:
    """A ground action with its preconditions (statics left out) and effects as atoms."""

    action: Action
    pre: tuple[tuple[Atom, int], ...]  # (atom, criticality), statics left out
    effects: tuple[Atom, ...]


def _args_maker(args: Sequence[Term], pos: dict[Var, int]) -> Callable[[_Args], _Args]:
    """A function from an instance's arguments to a template's ground arguments (C-level where it can be)."""
    idx = [pos.get(a, -1) if isinstance(a, Var) else -1 for a in args]
    if all(i >= 0 for i in idx):
        if len(idx) >= 2:
            return itemgetter(*idx)  # a tuple
        if len(idx) == 1:
            return itemgetter(slice(idx[0], idx[0] + 1))  # a 1-tuple (arguments are a tuple)
        return lambda xs: ()
    consts = list(args)
    spec = [(i, consts[n]) for n, i in enumerate(idx)]
    return lambda xs: tuple(xs[i] if i >= 0 else c for i, c in spec)


def _column(table: FactTable, pred: str, mk: Callable[[_Args], _Args], value: Any, pos: dict[Var, int],
            instances: list[_Args]) -> tuple[list[int], list[_Args]]:
    """The fact id of one template in every instance (and the instances' ground arguments for it)."""
    ground = list(map(mk, instances))
    if isinstance(value, Var) and value in pos:
        j = pos[value]
        keys = [(pred, a, xs[j]) for a, xs in zip(ground, instances, strict=True)]
    else:
        keys = [(pred, a, value) for a in ground]
    ids = list(map(table.by_key.get, keys))
    if None in ids:
        ids = [table.id_of(*k) if f is None else f for f, k in zip(ids, keys, strict=True)]
    return ids, ground  # type: ignore[return-value]


def instances(grounder: Grounder, op: Operator) -> list[_Args]:
    """The argument tuples of ``op``'s instances, those of ``grounder._fill(op, {})`` in its order.

    The same join of the static preconditions with the listed facts, then the product
    of typed objects, over an array of values by variable position instead of a
    binding dictionary per step (``tests/test_ground_task.py`` compares the two).
    """
    plan = grounder._fill_plan(op)
    names: list[Var] = list(op.params)
    for s_ in plan.statics:
        for a in s_.args:
            if isinstance(a, Var) and a not in names:
                names.append(a)  # a variable of a static precondition that is no parameter
    pos = {v: j for j, v in enumerate(names)}
    specs = [tuple(pos[a] if isinstance(a, Var) else -1 for a in s_.args) for s_ in plan.statics]
    consts = [tuple(s_.args) for s_ in plan.statics]
    later = [(s_.predicate, tuple(pos[a] if isinstance(a, Var) else -1 for a in s_.args), tuple(s_.args), s_.value)
             for s_ in plan.later]
    typed = [(pos[v], ok) for v, ok in plan.typed]
    allobj = plan.allobj
    n = len(op.params)
    domains = [grounder.objects_of(op.type_of(v)) for v in op.params]
    unset = object()
    cur: list[Any] = [unset] * len(names)
    out: list[_Args] = []
    facts_ok = grounder.lists_facts
    holds = grounder.static_holds

    def ground(spec: tuple[int, ...], args: tuple[Any, ...]) -> tuple[Any, ...] | None:
        vals = tuple(cur[j] if j >= 0 else c for j, c in zip(spec, args, strict=True))
        return None if any(v is unset for v in vals) else vals

    def emit() -> None:
        for j, ok in typed:
            v = cur[j]
            if v is not unset and isinstance(v, str) and v in allobj and v not in ok:
                return
        free = [j for j in range(n) if cur[j] is unset]
        for combo in itertools.product(*[domains[j] for j in free]):
            for j, v in zip(free, combo, strict=True):
                cur[j] = v
            if all((g := ground(spec, args)) is None or holds(Atom(pred, g, value))
                   for pred, spec, args, value in later):
                out.append(tuple(cur[:n]))
        for j in free:
            cur[j] = unset

    def join(i: int) -> None:
        if i == len(specs):
            emit()
            return
        s_, spec = plan.statics[i], specs[i]
        g = ground(spec, consts[i])
        if g is not None:
            if holds(Atom(s_.predicate, g, s_.value)):
                join(i + 1)
            return
        if not facts_ok or s_.value is not True:
            join(i + 1)
            return
        m = len(spec)
        for fact in grounder.belief.facts(s_.predicate):
            if len(fact) != m:
                continue
            bound: list[int] = []
            ok = True
            for j, c, v in zip(spec, consts[i], fact, strict=True):
                if j < 0:
                    if c != v:
                        ok = False
                        break
                elif cur[j] is unset:
                    cur[j] = v
                    bound.append(j)
                elif cur[j] != v:
                    ok = False
                    break
            if ok:
                join(i + 1)
            for j in bound:
                cur[j] = unset

    join(0)
    return out


def _state_free(c: StateFreeCost, op: Operator, args: tuple[Term, ...]) -> float | None:
    """Instance ``args`` of ``op`` costed once; ``None`` (asked when a search uses it, as any cost that
    reads the belief) where the cost cannot be had here: a PDDL cost function the :init leaves
    undefined for an instance no plan reaches (IPC-2011 elevators p12) must not fail a call."""
    try:
        return float(c(dict(zip(op.params, args, strict=True)), None))
    except Exception:  # (the domain's error, raised again where a search asks that action's cost)
        return None


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
        for i, instances in fills:
            op = self.operators[i]
            if not instances:
                continue
            pos = {v: j for j, v in enumerate(op.params)}
            pre_cols: list[list[tuple[int, int, int]]] = []
            for p in op.preconditions:
                a = p.atom
                if a.predicate in drop:
                    continue
                mk = _args_maker(a.args, pos)
                ids, ground = _column(table, a.predicate, mk, a.value, pos, instances)
                if isinstance(a.value, Var):
                    vals = [table.atoms[f].value for f in ids]
                    twins = [table.id_of(a.predicate, g, True) if v is False else -1
                             for g, v in zip(ground, vals, strict=True)]
                elif a.value is False:
                    twins = _column(table, a.predicate, mk, True, pos, instances)[0]
                else:
                    twins = [-1] * len(ids)
                crit = p.criticality
                pre_cols.append([(f, crit, t) for f, t in zip(ids, twins, strict=True)])
            eff_cols = [_column(table, e.predicate, _args_maker(e.args, pos), e.value, pos, instances)[0]
                        for e in op.effects]
            self.pre.extend(zip(*pre_cols) if pre_cols else [() for _ in instances])
            self.effects.extend(zip(*eff_cols) if eff_cols else [() for _ in instances])
            c = op.cost
            if isinstance(c, StateFreeCost):  # the same in every belief: a number per instance, once
                self.fixed_cost.extend([_state_free(c, op, xs) for xs in instances])
            else:
                self.fixed_cost.extend([None if callable(c) else float(c)] * len(instances))
            self.op.extend([i] * len(instances))
            self.args.extend(instances)
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

    def lowered(self, levels: LevelMap) -> dict[int, int]:
        """Per action ``k`` below ``levels.top`` in ``levels`` (an instance's own level, or its
        operator's floor) that level."""
        top = levels.top
        out: dict[int, int] = {}
        for key, lv in levels.overrides:
            k = self.index.get(key)
            if k is not None and lv != top:
                out[k] = lv
        for name, fl in levels.floors:
            if fl >= top:
                continue
            i = next((j for j, op in enumerate(self.operators) if op.name == name), None)
            if i is None:
                continue
            for k, o in enumerate(self.op):
                if o == i and out.get(k, top) > fl:
                    out[k] = fl
        return out

    def adders(self) -> dict[int, list[int]]:
        """Per fact id the actions (ascending) that add it."""
        if self._adders is None:
            self._adders = {}
            for k, effs in enumerate(self.effects):
                for e in effs:
                    self._adders.setdefault(e, []).append(k)
        return self._adders

    def pre_at(self, level: int) -> list[tuple[int, ...]]:
        """Per action its preconditions' facts kept at ``level`` (criticality above it), in order."""
        key = ("pre at", level)
        hit = self.memo.get(key)
        if not isinstance(hit, list):
            hit = self.memo[key] = [tuple([f for f, c, _ in pre if c > level]) for pre in self.pre]
        return hit

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
