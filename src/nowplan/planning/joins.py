"""Operators' conditions joined against reached facts, semi-naively (for :mod:`nowplan.planning.task_grounding`).

Relaxed reachability grounds an operator by joining its positive conditions
(the static ones and those kept at the level) against the facts reached so
far, round after round until no new fact appears.  Joining every operator
again in full each round re-derives every binding of the rounds before (on
IPC-2011 tidybot p04, 219,089 bindings for 29,889 actions).  The
semi-naive evaluation of Datalog (Bancilhon & Ramakrishnan 1986; Fast
Downward's translator grounds with a Datalog program too, Helmert 2009)
joins, after the first round, only the bindings that use at least one fact
new in the last round: for each condition whose predicate gained facts,
that condition first over the new facts (``delta``), then the others over
all facts.  A binding that uses no new fact was found in an earlier round,
since its facts were all there.

:class:`FactIndex` keeps the facts of a predicate by the values at some
argument positions; :class:`OperatorJoin` is one operator's join plan, the
most constrained condition first.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Iterator, Mapping
from typing import Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.operators import Operator

UNBOUND = object()  # a parameter slot no condition has bound yet

# per step: predicate, arity, bound positions, how to build the lookup key (slot or constant),
# and the positions that bind new slots (a slot repeated in one atom is checked after binding)
Step = tuple[str, int, tuple[int, ...], tuple[tuple[bool, Any], ...], tuple[tuple[int, int], ...]]
Table = dict[tuple[Any, ...], list[tuple[Any, ...]]]
# per step: (position in the fact, slot it binds, the objects of a wrong type for that slot or None)
Check = tuple[tuple[int, int, frozenset[str] | None], ...]


class FactIndex:
    """Facts of a predicate by the values at some argument positions, built on demand and extended by
    :meth:`extend` as the fixpoint reaches facts (not rebuilt every round: on visit-all 16x16 the
    rebuilds of the static ``connected`` tables took a third of the grounding)."""

    def __init__(self, facts: Mapping[str, set[tuple[Any, ...]]]) -> None:
        self.facts = facts
        self.tables: dict[tuple[str, tuple[int, ...]], Table] = {}
        self.by_pred: dict[str, list[tuple[tuple[int, ...], Table]]] = {}
        self.arity: dict[tuple[str, tuple[int, ...]], int] = {}

    def extend(self, new: Iterable[Atom]) -> None:
        """Add facts just reached (not in ``facts`` when the tables were built) to the tables built."""
        for e in new:
            for positions, t in self.by_pred.get(e.predicate, ()):
                if len(e.args) == self.arity[(e.predicate, positions)]:
                    t.setdefault(tuple(e.args[i] for i in positions), []).append(e.args)

    def lookup(self, pred: str, positions: tuple[int, ...], arity: int) -> Table:
        key = (pred, positions)
        t = self.tables.get(key)
        if t is None:
            t = {}
            for args in self.facts.get(pred, ()):
                if len(args) == arity:
                    t.setdefault(tuple(args[i] for i in positions), []).append(args)
            self.tables[key] = t
            self.by_pred.setdefault(pred, []).append((positions, t))
            self.arity[key] = arity
        return t


class OperatorJoin:
    """An operator's positive conditions compiled into join plans over parameter slots.

    The conditions joined are the static ones and those kept at ``level``;
    each step looks facts up by the slots already bound (an index per
    predicate and bound positions), then binds the rest.  :meth:`bindings`
    joins in full; :meth:`new_bindings` only what uses a fact of ``delta``.
    """

    def __init__(self, op: Operator, statics: frozenset[str], level: int,
                 facts: Mapping[str, set[tuple[Any, ...]]],
                 type_sets: Mapping[str | None, frozenset[str]]) -> None:
        self.op = op
        self._slot = {v: i for i, v in enumerate(op.params)}
        self.conds = [
            p.atom for p in op.preconditions
            if p.atom.value is True and (p.atom.predicate in statics or p.criticality > level)
        ]
        self.predicates = frozenset(c.predicate for c in self.conds)
        self._sizes = {c.predicate: len(facts.get(c.predicate, ())) for c in self.conds}
        self.typed = [(i, t) for i, t in enumerate(op.param_types) if t is not None] if op.param_types else []
        self._type_sets = type_sets
        objects = type_sets[None]
        # a slot's type is checked as soon as a fact binds it (a value that is not an object, e.g. a
        # number, passes, as in the final check of _bindings): a condition shared by several types
        # (logistics' ``at`` of packages and vehicles) then prunes the join early instead of
        # multiplying its partial bindings by the facts of the other types
        self._wrong = {sl: objects - type_sets.get(t, frozenset()) for sl, t in self.typed}
        steps, bound = self._plan(None)
        self._full = (steps, self._checks(steps))
        self._delta: dict[int, tuple[list[Step], list[Check]]] = {}
        self.free = [(i, op.param_types[i] if op.param_types else None)
                     for i, v in enumerate(op.params) if v not in bound]

    def _checks(self, steps: list[Step]) -> list[Check]:
        return [tuple((pos, sl, self._wrong.get(sl)) for pos, sl in binds) for *_, binds in steps]

    def _plan(self, first: int | None) -> tuple[list[Step], set[Var]]:
        """The join steps, ``conds[first]`` first if given, then the most constrained condition next
        (most arguments bound, then fewest facts when the join was made)."""
        slot = self._slot
        bound: set[Var] = set()
        steps: list[Step] = []
        remaining = list(self.conds)
        if first is not None:
            remaining.insert(0, remaining.pop(first))
        while remaining:
            if first is not None and not steps:
                best = remaining[0]
            else:
                best = max(remaining, key=lambda a: (
                    sum(1 for t in a.args if not isinstance(t, Var) or t in bound), -self._sizes[a.predicate]))
            remaining.remove(best)
            positions: list[int] = []
            keyparts: list[tuple[bool, Any]] = []
            binds: list[tuple[int, int]] = []
            fresh: set[Var] = set()
            for i, t in enumerate(best.args):
                if isinstance(t, Var):
                    if t in bound:
                        positions.append(i)
                        keyparts.append((True, slot[t]))
                    else:
                        binds.append((i, slot[t]))
                        fresh.add(t)
                else:
                    positions.append(i)
                    keyparts.append((False, t))
            bound |= fresh
            steps.append((best.predicate, len(best.args), tuple(positions), tuple(keyparts), tuple(binds)))
        return steps, bound

    def bindings(self, index: FactIndex, by_type: Mapping[str | None, list[str]]) -> Iterator[tuple[Any, ...]]:
        """Every binding of the parameters over ``index``'s facts (typed; free parameters by type)."""
        return self._bindings(*self._full, index, None, by_type)

    def new_bindings(self, index: FactIndex, delta: FactIndex, changed: set[str],
                     by_type: Mapping[str | None, list[str]]) -> Iterator[tuple[Any, ...]]:
        """The bindings over ``index``'s facts that use at least one fact of ``delta`` (whose
        predicates are ``changed``); a binding may come more than once."""
        for j, c in enumerate(self.conds):
            if c.predicate not in changed:
                continue
            plan = self._delta.get(j)
            if plan is None:
                steps = self._plan(j)[0]
                plan = self._delta[j] = (steps, self._checks(steps))
            yield from self._bindings(*plan, index, delta, by_type)

    def _bindings(self, steps: list[Step], checks: list[Check], index: FactIndex, delta: FactIndex | None,
                  by_type: Mapping[str | None, list[str]]) -> Iterator[tuple[Any, ...]]:
        n = len(self.op.params)
        type_sets = self._type_sets
        objects = type_sets[None]
        last = len(steps)

        def join(k: int, cur: list[Any]) -> Iterator[list[Any]]:
            if k == last:
                yield cur
                return
            pred, arity, positions, keyparts, _binds = steps[k]
            table = (delta if k == 0 and delta is not None else index).lookup(pred, positions, arity)
            key = tuple(cur[v] if is_slot else v for is_slot, v in keyparts)
            check = checks[k]
            for args in table.get(key, ()):
                nxt = list(cur)
                ok = True
                for pos, sl, bad in check:
                    have = nxt[sl]
                    v = args[pos]
                    if have is UNBOUND:
                        if bad and v in bad:
                            ok = False
                            break
                        nxt[sl] = v
                    elif have != v:
                        ok = False
                        break
                if ok:
                    yield from join(k + 1, nxt)

        for b in join(0, [UNBOUND] * n):
            if any(b[i] in objects and b[i] not in type_sets.get(t, ()) for i, t in self.typed
                   if b[i] is not UNBOUND):
                continue
            if not self.free:
                yield tuple(b)
                continue
            for combo in itertools.product(*(by_type.get(t, []) for _, t in self.free)):
                full = list(b)
                for (i, _), v in zip(self.free, combo, strict=True):
                    full[i] = v
                yield tuple(full)
