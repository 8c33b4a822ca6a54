"""The reachable ground actions of a problem, by relaxed reachability (for the forward task).

Grounding joins each operator's positive preconditions against the facts a
relaxed (delete-free) exploration reaches from the initial state, until a
fixpoint; parameters no such precondition binds are enumerated by type.
Static preconditions (predicates no operator changes) are checked at every
level, as the regression planner's grounder does; the others count only
when their criticality is kept at the action's level.  A grounding is
cached per (domain, objects, static facts, level) and reused for any later
state whose true facts it already reached (everything reachable from such a
state was reached too).  :func:`nowplan.planning.task.build_task` turns a
grounding into an integer task.
"""

from __future__ import annotations

import itertools
import logging
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.core.operators import Action, Operator

log = logging.getLogger(__name__)


@dataclass
class Grounding:
    """The reachable ground actions of a problem for one abstraction level."""

    actions: list[Action]
    reached: set[Atom]  # positive atoms reachable from the states seen so far
    statics: frozenset[str]
    operators: frozenset[str] | None = None  # the operators grounded (None: all)
    # filed by share_concrete (not grounded at its level): a call that needs fewer operators gets
    # them filtered from it (restricted), not this whole grounding
    shared: bool = False
    # integer task structures built from these actions (nowplan.planning.task), by level map and "not" facts
    tasks: dict[Any, Any] = field(default_factory=dict, repr=False)
    # effect atom -> the actions with that effect (made on the first ask, see adders_of)
    adders: dict[Atom, list[Action]] | None = field(default=None, repr=False)


def adders_of(g: Grounding) -> dict[Atom, list[Action]]:
    """Each effect atom of ``g``'s actions -> those actions, in grounding order (made once per grounding:
    the actions' effects are bound already, so this reads them and binds nothing)."""
    if g.adders is None:
        index: dict[Atom, list[Action]] = {}
        for act in g.actions:
            for e in act.effects():
                index.setdefault(e, []).append(act)
        g.adders = index
    return g.adders


def cached_grounding(domain: Domain, objects: Mapping[str, str | None], belief: Any,
                     level: int) -> Grounding | None:
    """The cached grounding of every operator at ``level`` that covers ``belief`` (it reached every
    fact true there), or None; never grounds (e.g. the one ``--criticality auto``'s set-up filed)."""
    base = _key_of(domain, objects, belief, domain.static_predicates, level)
    init = {a for a in belief.atoms() if a.value is True}
    for (b, ops), g in reversed(_CACHE.items()):  # the latest first
        if ops is None and b == base and init <= g.reached:
            return g
    return None


_CACHE: dict[Any, Grounding] = {}
_CACHE_SIZE = 16


def _key_of(domain: Domain, objects: Mapping[str, str | None], belief: Any, statics: frozenset[str],
            level: int) -> Any:
    facts = tuple(sorted((p, tuple(sorted(map(repr, belief.facts(p))))) for p in statics))
    # the domain itself (held by the cache, so its identity cannot be reused by another domain)
    # operators compare without their costs: two domains equal but for costs must not share actions
    costs = tuple(id(o.cost) if callable(o.cost) else o.cost for o in domain.operators)
    return (domain, costs, tuple(sorted(objects.items(), key=repr)), facts, level)


def grounding(domain: Domain, objects: Mapping[str, str | None], belief: Any, level: int,
              operators: frozenset[str] | None = None) -> Grounding:
    """The reachable actions for ``belief`` at ``level`` (cached across calls), of at least the
    operators named in ``operators`` (``None``: all; e.g. those relevant to a goal,
    :mod:`nowplan.planning.relevance`).

    A cached grounding of the same objects, static facts and level that covers ``belief`` (it
    reached every fact true there) serves if it has these operators; else the new grounding
    starts from the latest such grounding and adds what is missing (the union of the operators,
    and the facts ``belief`` adds), keeping its actions: a run whose goals need more and more of
    the domain grounds each action once."""
    statics = domain.static_predicates
    base = _key_of(domain, objects, belief, statics, level)
    init = {a for a in belief.atoms() if a.value is True}
    prev: Grounding | None = None
    for (b, ops), g in reversed(_CACHE.items()):  # the latest first
        if b != base:
            continue
        covers = init <= g.reached
        if covers and g.shared and operators is not None and (ops is None or operators < ops):
            return _file((base, operators), _restrict(g, operators, init, level, statics))
        if covers and (ops is None or (operators is not None and operators <= ops)):
            return g
        if prev is None or covers and not init <= prev.reached:
            prev = g
    if prev is not None:
        operators = None if operators is None or prev.operators is None else operators | prev.operators
    return _file((base, operators), _ground(domain, objects, init, statics, level, operators, prev))


def clear_cache() -> None:
    """Forget every cached grounding (a benchmark starts each run cold, as a fresh process does)."""
    _CACHE.clear()


def _file(key: Any, g: Grounding) -> Grounding:
    _CACHE.pop(key, None)
    if len(_CACHE) >= _CACHE_SIZE:
        _CACHE.pop(next(iter(_CACHE)))
    _CACHE[key] = g
    return g


def _restrict(g: Grounding, operators: frozenset[str], init: set[Atom], level: int,
              statics: frozenset[str]) -> Grounding:
    """What :func:`_ground` finds from ``init`` over ``operators``, filtered from ``g`` (a grounding
    of all operators whose atoms cover ``init``): every action reachable from ``init`` is in ``g``
    (reachability is monotone in the start), so a relaxed exploration over ``g``'s actions of these
    operators, joining the conditions :class:`_Join` joins (static or kept at ``level``), reaches the
    same atoms and actions without binding anything again."""
    acts = [a for a in g.actions if a.operator.name in operators]
    reached = set(init)
    waiting: dict[Atom, list[int]] = {}
    count = [0] * len(acts)
    queue: list[int] = []
    for i, a in enumerate(acts):
        conds = {p for p, pc in zip(a.preconditions(), a.operator.preconditions, strict=True)
                 if p.value is True and (p.predicate in statics or pc.criticality > level)}
        missing = [c for c in conds if c not in reached]
        for c in missing:
            waiting.setdefault(c, []).append(i)
        count[i] = len(missing)
        if not missing:
            queue.append(i)
    fired = [False] * len(acts)
    while queue:  # each action fires once: bounded by the actions
        i = queue.pop()
        fired[i] = True
        for e in acts[i].effects():
            if e.value is True and e not in reached:
                reached.add(e)
                for j in waiting.pop(e, ()):
                    count[j] -= 1
                    if count[j] == 0:
                        queue.append(j)
    return Grounding([a for a, f in zip(acts, fired, strict=True) if f], reached, statics, operators)


def _objects_by_type(domain: Domain, objects: Mapping[str, str | None]) -> dict[str | None, list[str]]:
    allobj = {**dict(domain.constants), **dict(objects)}
    out: dict[str | None, list[str]] = {None: sorted(allobj)}
    for t in list(domain.types) + [o for o in set(allobj.values()) if o is not None]:
        if t not in out:
            ok = domain.subtypes(t)
            out[t] = sorted(o for o, ot in allobj.items() if ot in ok)
    return out


def _ground(domain: Domain, objects: Mapping[str, str | None], start: set[Atom],
            statics: frozenset[str], level: int, operators: frozenset[str] | None = None,
            prev: Grounding | None = None) -> Grounding:
    """The fixpoint of relaxed reachability from ``start`` (and ``prev``'s facts) over the operators
    named in ``operators`` (``None``: all).  ``prev``, a grounding of the same objects, static facts and
    level, is extended: its actions are kept (the same objects, with their ground atoms), and when
    ``start`` adds no fact to it, the first round joins only the operators it did not have (it is a
    fixpoint for its own)."""
    by_type = _objects_by_type(domain, objects)
    type_sets = {t: frozenset(v) for t, v in by_type.items()}
    reached: set[Atom] = set(start) | (prev.reached if prev is not None else set())
    facts: dict[str, set[tuple[Any, ...]]] = {}
    for a in reached:
        facts.setdefault(a.predicate, set()).add(a.args)
    schemas = (*(op for op in domain.operators if operators is None or op.name in operators),
               *domain.axioms)  # an axiom's conditions are kept at every level
    joins = [_Join(op, statics, level, facts) for op in schemas]
    actions: list[Action] = list(prev.actions) if prev is not None else []
    seen: set[tuple[str, tuple[Any, ...]]] = {a.key for a in actions}
    fresh: set[str] | None = None  # the operators the first round joins (None: all)
    if prev is not None and start <= prev.reached:
        had = prev.operators
        fresh = set() if had is None else {op.name for op in schemas if op.name not in had}
    changed: set[str] | None = None  # predicates with new facts in the last round (None: all)
    index = _Index(facts)  # kept across rounds: each round's new facts are added to its tables
    while changed is None or changed:
        new: list[Atom] = []
        for op, join in zip(schemas, joins, strict=True):
            if changed is not None and not join.predicates & changed:
                continue  # nothing new to join against: the same bindings as last round
            if changed is None and fresh is not None and op.name not in fresh:
                continue  # ``prev`` has every binding of this operator over its facts
            for args in join.bindings(index, by_type, type_sets):
                key = (op.name, args)
                if key in seen:
                    continue
                act = Action(op, args)
                if not _negative_statics_hold(act, statics, facts):
                    continue
                seen.add(key)
                actions.append(act)
                for e in act.effects():
                    if e.value is True and e not in reached:
                        reached.add(e)
                        new.append(e)
        changed = set()
        for e in new:
            facts.setdefault(e.predicate, set()).add(e.args)
            changed.add(e.predicate)
        index.extend(new)
    return Grounding(_undominated(actions, statics, level), reached, statics, operators)


def _undominated(actions: list[Action], statics: frozenset[str], level: int) -> list[Action]:
    """``actions`` without the dominated variants of one PDDL action instance.

    An ADL action compiled to several operators (``NAME-v1``, ``NAME-v2``, ...) can give, for one
    binding of its parameters, variants with the same effects whose preconditions differ only in
    literals of static predicates: IPC-2006 trucks' ``(forall (?a2) (imply (closer ?a2 ?a1)
    (free ?a2 ?t)))`` is a disjunction per area, ``(not (closer ?a2 ?a1))`` or ``(free ?a2 ?t)``, so
    a variant may require ``free`` of an area that the static ``closer`` already excuses.  Grounding
    kept every such variant (336 loads for 72 bindings in trucks p07), which multiplies successors
    and achievers.  A variant is dropped when another of the same instance, with the same effects
    and cost, needs a subset of its non-static preconditions at this level (the statics of a
    grounded action hold): every plan using it can use the other one instead.
    """
    groups: dict[tuple[str, tuple[Any, ...]], list[Action]] = {}
    for act in actions:
        name = act.operator.pddl_name
        if name and act.cost_is_state_free:
            groups.setdefault((name, act.args), []).append(act)
    dropped: set[int] = set()
    for group in groups.values():
        if len(group) < 2:
            continue
        conds = [frozenset(a for a in act.preconditions(level) if a.predicate not in statics) for act in group]
        effs = [frozenset(act.effects()) for act in group]
        costs = [act.cost() for act in group]
        for i, act in enumerate(group):
            for j in range(len(group)):
                if j == i or id(group[j]) in dropped or effs[j] != effs[i] or costs[j] != costs[i]:
                    continue
                if conds[j] < conds[i] or (conds[j] == conds[i] and j < i):
                    dropped.add(id(act))
                    break
    if not dropped:
        return actions
    log.debug("grounding: %d dominated action variants dropped", len(dropped))
    return [a for a in actions if id(a) not in dropped]


def _negative_statics_hold(act: Action, statics: frozenset[str], facts: Mapping[str, set[Any]]) -> bool:
    for p in act.preconditions(None):
        if p.value is False and p.predicate in statics and p.args in facts.get(p.predicate, ()):
            return False
    return True


class _Index:
    """Facts of a predicate by the values at some argument positions, built on demand and extended by
    :meth:`extend` as the fixpoint reaches facts (not rebuilt every round: on visit-all 16x16 the
    rebuilds of the static ``connected`` tables took a third of the grounding)."""

    def __init__(self, facts: Mapping[str, set[tuple[Any, ...]]]) -> None:
        self.facts = facts
        self.tables: dict[tuple[str, tuple[int, ...]], dict[tuple[Any, ...], list[tuple[Any, ...]]]] = {}
        self.by_pred: dict[str, list[tuple[tuple[int, ...], dict[tuple[Any, ...], list[tuple[Any, ...]]]]]] = {}
        self.arity: dict[tuple[str, tuple[int, ...]], int] = {}

    def extend(self, new: Iterable[Atom]) -> None:
        """Add facts just reached (not in ``facts`` when the tables were built) to the tables built."""
        for e in new:
            for positions, t in self.by_pred.get(e.predicate, ()):
                if len(e.args) == self.arity[(e.predicate, positions)]:
                    t.setdefault(tuple(e.args[i] for i in positions), []).append(e.args)

    def lookup(self, pred: str, positions: tuple[int, ...], arity: int) -> dict[tuple[Any, ...], list[tuple[Any, ...]]]:
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


class _Join:
    """An operator's positive conditions compiled into a join plan over parameter slots.

    The conditions joined are the static ones and those kept at ``level``;
    each step looks facts up by the slots already bound (an index per
    predicate and bound positions), then binds the rest.
    """

    def __init__(self, op: Operator, statics: frozenset[str], level: int,
                 facts: Mapping[str, set[tuple[Any, ...]]]) -> None:
        self.op = op
        slot = {v: i for i, v in enumerate(op.params)}
        conds = [
            p.atom for p in op.preconditions
            if p.atom.value is True and (p.atom.predicate in statics or p.criticality > level)
        ]
        self.predicates = frozenset(c.predicate for c in conds)
        bound: set[Var] = set()
        # per step: predicate, arity, bound positions, how to build the lookup key (slot or constant),
        # and the positions that bind new slots (a slot repeated in one atom is checked after binding)
        self.steps: list[tuple[str, int, tuple[int, ...], tuple[tuple[bool, Any], ...],
                               tuple[tuple[int, int], ...]]] = []
        remaining = list(conds)
        while remaining:  # the most constrained condition first
            best = max(remaining, key=lambda a: (
                sum(1 for t in a.args if not isinstance(t, Var) or t in bound),
                -len(facts.get(a.predicate, ()))))
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
            self.steps.append((best.predicate, len(best.args), tuple(positions), tuple(keyparts), tuple(binds)))
        self.free = [(i, op.param_types[i] if op.param_types else None)
                     for i, v in enumerate(op.params) if v not in bound]
        self.typed = [(i, t) for i, t in enumerate(op.param_types) if t is not None] if op.param_types else []
        self.slot_type: dict[int, str] = dict(self.typed)

    def bindings(self, index: _Index, by_type: Mapping[str | None, list[str]],
                 type_sets: Mapping[str | None, frozenset[str]]) -> Iterator[tuple[Any, ...]]:
        n = len(self.op.params)
        steps = self.steps
        objects = type_sets[None]
        # a slot's type is checked as soon as a fact binds it (a value that is not an object, e.g. a
        # number, passes, as in the final check below): a condition shared by several types (logistics'
        # ``at`` of packages and vehicles) then prunes the join early instead of multiplying its partial
        # bindings by the facts of the other types
        wrong = {sl: objects - type_sets.get(t, frozenset()) for sl, t in self.slot_type.items()}
        checks = [tuple((pos, sl, wrong.get(sl)) for pos, sl in binds) for *_, binds in steps]

        def join(k: int, cur: list[Any]) -> Iterator[list[Any]]:
            if k == len(steps):
                yield cur
                return
            pred, arity, positions, keyparts, _binds = steps[k]
            table = index.lookup(pred, positions, arity)
            key = tuple(cur[v] if is_slot else v for is_slot, v in keyparts)
            check = checks[k]
            for args in table.get(key, ()):
                nxt = list(cur)
                ok = True
                for pos, sl, bad in check:
                    have = nxt[sl]
                    v = args[pos]
                    if have is _UNBOUND:
                        if bad and v in bad:
                            ok = False
                            break
                        nxt[sl] = v
                    elif have != v:
                        ok = False
                        break
                if ok:
                    yield from join(k + 1, nxt)

        for b in join(0, [_UNBOUND] * n):
            if any(b[i] in objects and b[i] not in type_sets.get(t, ()) for i, t in self.typed
                   if b[i] is not _UNBOUND):
                continue
            if not self.free:
                yield tuple(b)
                continue
            for combo in itertools.product(*(by_type.get(t, []) for _, t in self.free)):
                full = list(b)
                for (i, _), v in zip(self.free, combo, strict=True):
                    full[i] = v
                yield tuple(full)


_UNBOUND = object()


def _extension(old: Operator, op: Operator | None) -> tuple[int, tuple[int | None, ...]] | None:
    """How ``op`` extends ``old`` with preconditions only (see :func:`share_concrete`), or None.
    The old preconditions' criticalities may differ (the caller says every one is kept at its levels)."""
    k = len(old.preconditions)
    if (op is None or op.effects != old.effects or op.params != old.params or len(op.preconditions) < k
            or any(p.atom != q.atom for p, q in zip(op.preconditions, old.preconditions))):
        return None
    sources: list[int | None] = []
    for p in op.preconditions[k:]:
        v = p.atom.value
        j = next((i for i, q in enumerate(old.preconditions) if q.atom.args == p.atom.args), None)
        sources.append(j if not isinstance(v, Var) else None)
    return k, tuple(sources)


def share_concrete(concrete: Grounding, domain: Domain, objects: Mapping[str, str | None], belief: Any,
                   levels: Iterable[int]) -> None:
    """File ``concrete`` (the grounding at level -1 of a domain that ``domain`` extends with static
    preconditions only, or with other criticalities that keep every precondition at ``levels``) as
    ``domain``'s grounding at each of ``levels``, its actions re-made on ``domain``'s operators: what
    :func:`grounding` would compute there, without grounding again.

    The caller guarantees the premise (:func:`nowplan.planning.reach_statics.add_reachability_statics`:
    every precondition an abstract level drops is guarded by a static that holds exactly for the
    concretely reachable atoms, and every grounded action satisfies its new statics; the flat domain
    of ``--criticality auto``'s dead-end fallback, :func:`nowplan.planning.problem_hierarchy.prepare_problem`:
    every precondition kept at every level, as at level -1).  Then at every
    level the relaxed exploration from ``belief`` reaches the same atoms and actions as concretely:
    an action found there has its dropped preconditions reachable, hence all of them.  So the run's
    first planner call does not ground the problem a second time (``--criticality auto`` grounded it
    once to find the reachability statics).  The actions of an operator that gained no precondition
    are the same objects; for the others, the effects and the old preconditions, bound already, are
    carried over.
    """
    ops = {op.name: op for op in domain.operators}
    statics = domain.static_predicates
    actions: list[Action] = []
    # per operator, checked once: how each added precondition is made from the old bound ones (the
    # index of an old precondition with the same argument terms, whose bound arguments it takes, as
    # reachable-p(x) takes p(x)'s; else None: bound here)
    plans: dict[str, tuple[int, tuple[int | None, ...]] | None] = {}
    for old in concrete.actions:
        op = ops.get(old.operator.name)
        if op is old.operator:  # an operator that gained no precondition: its actions are the same
            actions.append(old)
            continue
        if old.operator.name not in plans:
            plans[old.operator.name] = _extension(old.operator, op)
        plan = plans[old.operator.name]
        if plan is None or op is None:
            return  # not an extension of the concrete domain's operators: ground as usual
        k, sources = plan
        act = Action(op, old.args)
        # the same effects and the old preconditions, bound once; only the added ones are made here
        act._ground["effects"] = old.effects()
        if sources:
            pres = old.preconditions()
            b: dict[Var, Any] | None = None
            extra: list[Atom] = []
            for p, j in zip(op.preconditions[k:], sources, strict=True):
                if j is not None:
                    extra.append(Atom(p.atom.predicate, pres[j].args, p.atom.value))
                else:
                    if b is None:
                        b = act.bindings
                    extra.append(p.atom.bind(b))
            act._ground[None] = (*pres, *extra)
        else:
            act._ground[None] = old.preconditions()
        actions.append(act)
    init = {a for a in belief.atoms() if a.value is True}
    reached = set(concrete.reached) | init
    for level in levels:
        _file((_key_of(domain, objects, belief, statics, level), None),
              Grounding(list(actions), reached, statics, None, shared=True))
