"""The reachable ground actions of a problem, by relaxed reachability (for the forward task).

Grounding joins each operator's positive preconditions against the facts a
relaxed (delete-free) exploration reaches from the initial state, until a
fixpoint (semi-naively: after the first round only the bindings that use a
new fact, :mod:`nowplan.planning.joins`); parameters no such precondition
binds are enumerated by type.
Static preconditions (predicates no operator changes) are checked at every
level, as the regression planner's grounder does; the others count only
when their criticality is kept at the action's level.  A grounding is
cached per (domain, objects, static facts, level) and reused for any later
state whose true facts it already reached (everything reachable from such a
state was reached too).  :func:`nowplan.planning.task.build_task` turns a
grounding into an integer task.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.core.operators import Action, Operator
from nowplan.planning.forward_generators import GeneratorFilter
from nowplan.planning.generators_run import Misses
from nowplan.planning.joins import FactIndex, OperatorJoin

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
    # generator calls whose proposals all disagreed with a bound output (forward_generators)
    misses: Misses | None = field(default=None, repr=False)


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
            level: int, generator_values: int = 8) -> Any:
    facts = tuple(sorted((p, tuple(sorted(map(repr, belief.facts(p))))) for p in statics))
    # the domain itself (held by the cache, so its identity cannot be reused by another domain)
    # operators compare without their costs: two domains equal but for costs must not share actions
    costs = tuple(id(o.cost) if callable(o.cost) else o.cost for o in domain.operators)
    # generators read the belief: their actions serve this state only (forward_generators); and
    # operators compare without their generators' functions (held by the cached domain: ids unique)
    state = None
    if _has_generators(domain):
        fns = tuple(id(g.fn) for o in domain.operators for g in o.generators)
        state = (frozenset(belief.atoms()), generator_values, fns)
    return (domain, costs, tuple(sorted(objects.items(), key=repr)), facts, level, state)


def _has_generators(domain: Domain) -> bool:
    return any(op.generators for op in domain.operators)


def grounding(domain: Domain, objects: Mapping[str, str | None], belief: Any, level: int,
              operators: frozenset[str] | None = None, generator_values: int = 8) -> Grounding:
    """The reachable actions for ``belief`` at ``level`` (cached across calls), of at least the
    operators named in ``operators`` (``None``: all; e.g. those relevant to a goal,
    :mod:`nowplan.planning.relevance`).

    A cached grounding of the same objects, static facts and level that covers ``belief`` (it
    reached every fact true there) serves if it has these operators; else the new grounding
    starts from the latest such grounding and adds what is missing (the union of the operators,
    and the facts ``belief`` adds), keeping its actions: a run whose goals need more and more of
    the domain grounds each action once.  Operators with generators (that read nothing of the goal)
    keep the bindings their generators propose from ``belief``, at most ``generator_values`` per call
    (:mod:`nowplan.planning.forward_generators`), and such a grounding serves ``belief``'s state only."""
    statics = domain.static_predicates
    base = _key_of(domain, objects, belief, statics, level, generator_values)
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
    gens = None
    if _has_generators(domain):
        gens = GeneratorFilter(belief, frozenset({**dict(domain.constants), **dict(objects)}), generator_values)
    return _file((base, operators), _ground(domain, objects, init, statics, level, operators, prev, gens))


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
    operators, joining the conditions :class:`~nowplan.planning.joins.OperatorJoin` joins (static or kept at ``level``), reaches the
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
            prev: Grounding | None = None, gens: GeneratorFilter | None = None) -> Grounding:
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
    joins = [OperatorJoin(op, statics, level, facts, type_sets) for op in schemas]
    actions: list[Action] = list(prev.actions) if prev is not None else []
    seen: set[tuple[str, tuple[Any, ...]]] = {a.key for a in actions}
    fresh: set[str] | None = None  # the operators the first round joins (None: all)
    if prev is not None and start <= prev.reached:
        had = prev.operators
        fresh = set() if had is None else {op.name for op in schemas if op.name not in had}
    changed: set[str] | None = None  # predicates with new facts in the last round (None: all)
    index = FactIndex(facts)  # kept across rounds: each round's new facts are added to its tables
    delta = FactIndex({})  # the facts new in the last round (semi-naive rounds, see joins.py)
    while changed is None or changed:
        new: list[Atom] = []
        for op, join in zip(schemas, joins, strict=True):
            if changed is not None and not join.predicates & changed:
                continue  # nothing new to join against: the same bindings as last round
            if changed is None and fresh is not None and op.name not in fresh:
                continue  # ``prev`` has every binding of this operator over its facts
            found = (join.bindings(index, by_type) if changed is None
                     else join.new_bindings(index, delta, changed, by_type))
            for args in found:
                key = (op.name, args)
                if key in seen:
                    continue
                act = Action(op, args)
                if not _negative_statics_hold(act, statics, facts):
                    continue
                if gens is not None and op.generators and not gens.accepts(op, args):
                    continue  # not a value the generators propose (NotEnumerable: not an object)
                seen.add(key)
                actions.append(act)
                for e in act.effects():
                    if e.value is True and e not in reached:
                        reached.add(e)
                        new.append(e)
        changed = set()
        news: dict[str, set[tuple[Any, ...]]] = {}
        for e in new:
            facts.setdefault(e.predicate, set()).add(e.args)
            news.setdefault(e.predicate, set()).add(e.args)
            changed.add(e.predicate)
        index.extend(new)
        delta = FactIndex(news)
    return Grounding(_undominated(actions, statics, level), reached, statics, operators,
                     misses=gens.misses if gens is not None and gens.misses else None)


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
