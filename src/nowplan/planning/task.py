"""An integer STRIPS task for forward search, grounded by relaxed reachability.

In the style of Fast Downward's translator and search code: atoms become
fact ids, a ground action becomes tuples of precondition, add and delete
ids, and a state is a ``frozenset`` of the true fact ids.  The ground
actions come from :mod:`nowplan.planning.task_grounding` (relaxed
reachability, cached per problem and level).

Negative conditions are compiled into facts of their own ("not p"): an
action that deletes ``p`` adds ``not p`` and one that adds ``p`` deletes it
(FD's translation of negative preconditions).  At an abstraction level an
action's hidden preconditions are not checked, so its adds also delete
every fact the domain's conflict rules (mutexes) exclude: the regression
planner assumes the same when it refuses a pre-image that conflicts with an
action's effects, so plans found forward regress into exact pre-images.

The grounding itself (relaxed reachability, cached) is in
:mod:`nowplan.planning.task_grounding`; ``Grounding`` and ``grounding`` are
re-exported here (``__all__``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom, Goal, KeyedRule
from nowplan.belief.protocols import HasUnknowns, ListsFacts, offers
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.fact_mutex import Excluder, FactMutex
from nowplan.planning.forward_generators import generators_unsupported
from nowplan.planning.relevance import relevant_operators
from nowplan.planning.task_grounding import Grounding, grounding

__all__ = [
    "FactMutex",
    "GroundAxioms",
    "Grounding",
    "Task",
    "build_task",
    "forward_unsupported",
    "grounding",
]


def forward_unsupported(domain: Domain, belief: Any) -> str | None:
    """Why forward search cannot run on this domain and belief, or ``None`` if it can."""
    if not offers(belief, ListsFacts):
        return "the belief does not list its facts"
    if offers(belief, HasUnknowns) and belief.unknowns():
        return "the belief is unsure of some fluents either way (a forward state is a closed world)"
    why = generators_unsupported(domain)  # generators that read nothing of the goal are grounded
    if why is not None:
        return why
    for p in domain.predicates.values():
        if p.test is not None:
            return f"predicate {p.name} has a test"
        if not p.boolean:
            return f"predicate {p.name} is not boolean"
    for op in domain.operators:
        atoms = [pc.atom for pc in op.preconditions] + list(op.effects)
        if any(not isinstance(a.value, bool) for a in atoms):
            return f"operator {op.name} has a non-boolean condition or effect"
    return None


# --------------------------------------------------------------------------- the task


@dataclass(frozen=True)
class GroundAxioms:
    """The ground rules of a task, ordered by stratum (layer)."""

    body: tuple[tuple[int, ...], ...]  # rule -> its condition facts ("not" facts included)
    head: tuple[int, ...]  # rule -> the derived fact it makes true
    layers: tuple[tuple[int, int], ...]  # layer -> its rules [lo, hi)
    negs: tuple[tuple[tuple[int, int], ...], ...]  # layer -> (d or -1, "not d") set after the layer
    derived: frozenset[int]  # every fact the evaluation recomputes (derived atoms, their "not" facts)

    def __bool__(self) -> bool:
        return bool(self.body) or bool(self.derived)



@dataclass
class Task:
    """Integer actions at one level map: ``pre``/``add``/``dele`` are fact-id tuples."""

    facts: list[Atom]  # id -> atom (value False for a compiled "not" fact)
    index: dict[Atom, int]
    actions: list[Action]
    pre: list[tuple[int, ...]]
    add: list[tuple[int, ...]]
    dele: list[tuple[int, ...]]
    cost: list[float]
    init: frozenset[int]
    goal: tuple[int, ...]
    unsolvable: str = ""  # why the goal cannot be reached (a goal atom never reachable)
    by_pre: dict[int, list[int]] = field(default_factory=dict)  # fact -> actions that need it
    no_pre: list[int] = field(default_factory=list)  # actions with no preconditions
    # the ground rules of derived predicates, evaluated after every action (nowplan.planning.axioms)
    axioms: GroundAxioms | None = None
    memo: dict[str, Any] = field(default_factory=dict, repr=False)  # what searches derive once per task

    def index_preconditions(self) -> None:
        """Fill ``by_pre`` and ``no_pre`` from ``pre``."""
        self.by_pre.clear()
        self.no_pre.clear()
        for k, p in enumerate(self.pre):
            if not p:
                self.no_pre.append(k)
            for f in p:
                self.by_pre.setdefault(f, []).append(k)


def pre_rows(task: Task) -> list[Sequence[int]]:
    """Per fact id, the actions that need it (``by_pre`` as a list; what the compiled heuristics take),
    made once per task, and once per shared structure for the tasks whose rows it serves
    (satellite, 50 images, --criticality auto: 152 planner calls spent 0.85 s of 11.9 profiled making
    it again)."""
    rows = task.memo.get("pre_rows")
    if rows is None:
        by_pre = task.by_pre
        rows = task.memo["pre_rows"] = [by_pre.get(f, ()) for f in range(len(task.facts))]
    return rows


@dataclass
class _Structure:
    """What the tasks of one grounding, level map and set of "not" facts share across calls."""

    facts: list[Atom]
    index: dict[Atom, int]
    actions: list[Action]
    pre: list[tuple[int, ...]]
    add: list[tuple[int, ...]]
    dele: list[tuple[int, ...]]
    negs: frozenset[Atom]  # the positive atoms whose "not" fact the task has
    axioms: GroundAxioms | None
    by_pre: dict[int, list[int]]
    no_pre: list[int]
    mutex: FactMutex | None
    rows: _Rows  # makes an action's row at another level (the level map's overrides)
    position: dict[Any, int] = field(default_factory=dict)  # action key -> its id
    costs: list[float] | None = None  # each action's cost, where every cost is state-free
    full_pre: list[tuple[int, ...]] | None = None  # each action's concrete preconditions (-1: not indexed)
    adders: dict[int, list[int]] | None = None  # fact -> the actions whose row adds it, ascending
    by_operator: dict[str, list[int]] | None = None  # operator name -> its actions' ids (floors move them)
    pre_rows: list[Sequence[int]] | None = None  # pre_rows of the tasks whose by_pre is this structure's


_STRUCTURES_PER_GROUNDING = 12


def build_task(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap,
    cost_of: Any,
    *,
    cache_costs: bool = False,
    relevant_to: Goal | None = None,
    hidden_costs: bool = False,
    generator_values: int = 8,
) -> Task:
    """The integer task for ``goal`` from ``belief`` with each action at its level in ``levels``.

    The actions are the (cached) grounding's, so the task's actions, facts and
    ids do not depend on the state: they are built once per grounding, level
    map without its overrides, and set of negative goal atoms, and shared by
    later calls (the executive's many calls on one problem); a call sets the
    costs, the initial state and the goal, and rebuilds the rows of the few
    actions its level map overrides.  Actions a relaxed exploration from this
    state does not reach never apply (the heuristics explore from the state).  The "not"
    facts are those of every action's full preconditions, whatever its level,
    so a row at any level finds its facts.  With ``cache_costs`` (``cost_of`` is
    ``Action.cost`` in the call's belief) and every cost state-free
    (:attr:`Action.cost_is_state_free`), the costs are kept with the structure.

    Only the operators relevant to ``goal`` and ``relevant_to`` (:mod:`nowplan.planning.relevance`, with
    the preconditions of the map's lowest level, a superset of every action's own) are grounded; the
    executive passes its problem's goal as ``relevant_to``, so the calls of a run share one grounding
    (an abstract level's goal hides most of some domains: where the lift is in miconic).

    ``hidden_costs``: an action that hides preconditions at its level costs its own cost plus
    ``h_max`` of the hidden ones from this state (:mod:`nowplan.planning.hidden_costs`), where the
    domain's operators do not all cost the same (:func:`~nowplan.planning.hidden_costs.varied_costs`; else the task's costs stand).
    ``generator_values``: at most this many values per generator call, for operators with generators
    that read nothing of the goal (:mod:`nowplan.planning.forward_generators`).
    """
    top = max([levels.top, *(lv for _, lv in levels.overrides)])
    low = min([levels.top, *(lv for _, lv in levels.overrides), *(lv for _, lv in levels.floors)])
    gr = grounding(domain, objects, belief, top, relevant_operators(domain, objects, goal, low, relevant_to),
                   generator_values=generator_values)
    statics = gr.statics
    true_now = {a for a in belief.atoms() if a.value is True}
    goal_negs = frozenset(a.negate() for a in goal.atoms if a.value is False and a.predicate not in statics)
    # the structure is the map's without overrides and floors: the actions these move get their rows anew
    st = _structure(domain, gr, dataclasses.replace(levels, overrides=frozenset(), floors=frozenset()), goal_negs)
    if any(fl < levels.top for _, fl in levels.floors):  # the floored structure, kept too: its rows move once
        st = _floored(domain, gr, st, dataclasses.replace(levels, overrides=frozenset()), goal_negs)
    pre, add, dele, by_pre, no_pre = st.pre, st.add, st.dele, st.by_pre, st.no_pre
    moved = sorted({st.position[key] for key, _ in levels.overrides if key in st.position})
    if moved:
        pre, add, dele = list(pre), list(add), list(dele)
        for k in moved:
            pre[k], add[k], dele[k] = st.rows.row(st.actions[k], levels.level(st.actions[k]))
        by_pre, no_pre = _reindexed(st.by_pre, st.no_pre, st.pre, pre, moved)
    init = frozenset({st.index[a] for a in true_now if a in st.index}
                     | {st.index[n.negate()] for n in st.negs if n not in true_now})
    if cache_costs and st.costs is not None:
        cost = st.costs
    else:
        cost = [float(cost_of(act)) for act in st.actions]
        if cache_costs and all(act.cost_is_state_free for act in st.actions):
            st.costs = cost
    task = Task(st.facts, st.index, st.actions, pre, add, dele, cost, init, (),
                by_pre=by_pre, no_pre=no_pre, axioms=st.axioms)
    if gr.misses:
        task.memo["generator misses"] = gr.misses  # (named if the search fails: forward.forward_plan)
    if by_pre is st.by_pre:  # no row moved: the structure's fact -> actions rows serve this task
        if st.pre_rows is None:
            st.pre_rows = pre_rows(task)
        task.memo["pre_rows"] = st.pre_rows
    if st.axioms is not None:
        from nowplan.planning.axioms import evaluator

        ev = evaluator(task)
        if ev is not None:
            task.init = ev.evaluate(task.init)
    goal_ids: list[int] = []
    for a in goal.atoms:
        if a.predicate in statics:
            if not domain.holds(a, belief):
                task.unsolvable = f"the goal needs {a}, a static fact that is false"
            continue
        i = st.index.get(a)
        if i is None:
            task.unsolvable = f"the goal needs {a}, which no action sequence reaches"
            continue
        goal_ids.append(i)
    task.goal = tuple(sorted(goal_ids))
    if st.mutex is not None:
        task.memo["mutex"] = st.mutex
    task.memo["position"] = st.position
    task.memo["adders"] = _adders(st, add, moved)
    # (not a concrete call; not in a domain whose operators all cost the same: see hidden_costs' module text)
    if hidden_costs and st.axioms is None and levels.top >= domain.min_criticality:
        from nowplan.planning.hidden_costs import add_hidden_costs, varied_costs

        costed = add_hidden_costs(len(st.facts), task.init, pre, _full_pre(st), add, cost) \
            if varied_costs(domain) else None
        if costed is not None:
            task.cost = costed
    return task


def _full_pre(st: _Structure) -> list[tuple[int, ...]]:
    """Each action's concrete non-static preconditions as fact ids (-1 for an atom the task does not
    index), made once per structure."""
    if st.full_pre is None:
        index, statics = st.index, st.rows.statics
        st.full_pre = [tuple(sorted({index.get(c, -1) for c in act.preconditions(None)
                                     if c.predicate not in statics}))
                       for act in st.actions]
    return st.full_pre


def _floored(domain: Domain, gr: Grounding, st: _Structure, floored: LevelMap, goal_negs: frozenset[Atom]) -> _Structure:
    """``st`` (the structure of the map without floors) with the rows of the floored operators' actions
    at their floors (``floored``: the map's floors, no overrides); kept on the grounding beside ``st``,
    so the refinements planned again under one floor (acting/refine.py) move those rows once."""
    store = gr.tasks
    key = (floored, goal_negs)
    hit: _Structure | None = store.get(key)
    if hit is not None:
        return hit
    if st.by_operator is None:
        st.by_operator = {}
        for k, act in enumerate(st.actions):
            st.by_operator.setdefault(act.operator.name, []).append(k)
    moved = sorted(k for name, fl in floored.floors if fl < floored.top for k in st.by_operator.get(name, ()))
    pre, add, dele = list(st.pre), list(st.add), list(st.dele)
    for k in moved:
        pre[k], add[k], dele[k] = st.rows.row(st.actions[k], floored.level(st.actions[k]))
    by_pre, no_pre = _reindexed(st.by_pre, st.no_pre, st.pre, pre, moved)
    hit = dataclasses.replace(st, pre=pre, add=add, dele=dele, by_pre=by_pre, no_pre=no_pre, adders=None)
    if len(store) >= _STRUCTURES_PER_GROUNDING:
        store.pop(next(iter(store)))
    store[key] = hit
    return hit


def _adders(st: _Structure, add: list[tuple[int, ...]], moved: list[int]) -> dict[int, list[int]]:
    """Fact -> the actions adding it (landmarks read it): the structure's, with the moved rows patched."""
    if st.adders is None:
        st.adders = {}
        for k, row in enumerate(st.add):
            for f in row:
                st.adders.setdefault(f, []).append(k)
    if not moved:
        return st.adders
    gone = set(moved)
    extra: dict[int, list[int]] = {}
    touched: set[int] = set()
    for k in moved:
        touched.update(st.add[k])
        for f in add[k]:
            extra.setdefault(f, []).append(k)
    touched.update(extra)
    out = dict(st.adders)
    for f in touched:
        acts = [x for x in st.adders.get(f, []) if x not in gone]
        more = extra.get(f)
        if more:
            acts = sorted(acts + more)
        out[f] = acts
    return {f: r for f, r in out.items() if r}


def _reindexed(by_pre: dict[int, list[int]], no_pre: list[int], old: list[tuple[int, ...]],
               new: list[tuple[int, ...]], moved: list[int]) -> tuple[dict[int, list[int]], list[int]]:
    """The successor index (fact -> the actions needing it, ascending; the actions needing nothing)
    with the rows of ``moved`` changed from ``old`` to ``new`` (each list touched is rebuilt once)."""
    gone = set(moved)
    adds: dict[int, list[int]] = {}
    touched: set[int] = set()
    for k in moved:
        touched.update(old[k])
        for f in new[k]:
            adds.setdefault(f, []).append(k)
    touched.update(adds)
    out = dict(by_pre)
    for f in touched:
        row = [x for x in by_pre.get(f, []) if x not in gone]
        extra = adds.get(f)
        if extra:
            row = sorted(row + extra)
        if row:
            out[f] = row
        else:
            out.pop(f, None)
    free = sorted([x for x in no_pre if x not in gone] + [k for k in moved if not new[k]])
    return out, free


def _structure(domain: Domain, gr: Grounding, base: LevelMap, goal_negs: frozenset[Atom]) -> _Structure:
    """The state-free part of the task at ``base`` (a level map without overrides; cached on the grounding)."""
    store = gr.tasks
    key = (base, goal_negs)
    hit: _Structure | None = store.get(key)
    if hit is not None:
        return hit
    hit = _build_structure(domain, gr, base, goal_negs)
    if len(store) >= _STRUCTURES_PER_GROUNDING:
        store.pop(next(iter(store)))
    store[key] = hit
    return hit


def _build_structure(domain: Domain, gr: Grounding, base: LevelMap, goal_negs: frozenset[Atom]) -> _Structure:
    statics = gr.statics
    names = _axiom_names(domain)
    # canonical (the same call makes the same plan, whatever the cache saw) and in the domain's order of
    # operators, as planners generate successors: the order breaks the search's ties (floor-tile: 92
    # expansions in Fast Downward's order, 19,246 in name order)
    rank = {op.name: i for i, op in enumerate(domain.operators)}
    ordered = sorted(gr.actions, key=lambda a: (rank.get(a.operator.name, len(rank)), a.name, repr(a.args)))
    kept = [act for act in ordered if act.operator.name not in names]
    rules = [(act, [p for p in act.preconditions(base.level(act)) if p.predicate not in statics])
             for act in ordered if act.operator.name in names]
    negs: set[Atom] = set(goal_negs)  # the positive atoms whose negation is a condition somewhere
    reached = set(gr.reached)
    for act in kept:
        negs.update(p.negate() for p in act.preconditions(None) if p.value is False and p.predicate not in statics)
        reached.update(p for p in act.preconditions(None) if p.value is True and p.predicate not in statics)
    for _, conds in rules:
        negs.update(p.negate() for p in conds if p.value is False)
    for act, _ in rules:
        reached.update(e for e in act.effects() if e.value is True)
    for act in kept:
        reached.update(e for e in act.effects() if e.value is True)
    # ids in a canonical order, whatever the cache saw before: the same call makes the same plan
    facts = sorted(reached, key=_atom_order)
    facts += [a.negate() for a in sorted(negs, key=_atom_order)]
    index = {a: i for i, a in enumerate(facts)}
    rows = _Rows(domain, statics, index, frozenset(negs), reached)
    pre: list[tuple[int, ...]] = []
    add: list[tuple[int, ...]] = []
    dele: list[tuple[int, ...]] = []
    for act in kept:
        p, a, d = rows.row(act, base.level(act))
        pre.append(p)
        add.append(a)
        dele.append(d)
    axioms = _ground_axioms(domain, rules, index, negs) if domain.axioms else None
    shell = Task(facts, index, kept, pre, add, dele, [], frozenset(), ())
    shell.index_preconditions()
    keyed = [c for c in domain.rules.conflicts if isinstance(c, KeyedRule)]
    mutex = FactMutex(facts, keyed) if keyed else None
    return _Structure(facts, index, kept, pre, add, dele, frozenset(negs), axioms, shell.by_pre,
                      shell.no_pre, mutex, rows, {act.key: i for i, act in enumerate(kept)})


class _Rows:
    """An action's precondition, add and delete fact ids at a level."""

    def __init__(self, domain: Domain, statics: frozenset[str], index: dict[Atom, int], negs: frozenset[Atom],
                 reached: set[Atom]) -> None:
        self.domain, self.statics, self.index, self.negs, self.reached = domain, statics, index, negs, reached
        self._excluder: Excluder | None = None
        # per added atom, the ids its exclusions delete (the atoms) and add (their "not" facts)
        self._excluded_ids: dict[Atom, tuple[frozenset[int], frozenset[int]]] = {}

    def row(self, act: Action, level: int) -> tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...]]:
        index, negs = self.index, self.negs
        conds = [p for p in act.preconditions(level) if p.predicate not in self.statics]
        p_ids = tuple(sorted({index[c] for c in conds}))
        adds = {e for e in act.effects() if e.value is True}
        dels = {e.negate() for e in act.effects() if e.value is False} - adds
        a_ids = {index[e] for e in adds if e in index}
        d_ids = {index[e] for e in dels if e in index}
        a_ids |= {index[e.negate()] for e in dels if e in negs}
        not_adds = {index[e.negate()] for e in adds if e in negs}
        d_ids |= not_adds
        if adds and self.domain.rules.conflicts and not act.is_primitive(level):
            # what the conflict rules exclude once ``adds`` hold is deleted too (kept as ids per atom:
            # an abstract level's task has one row per action, and the atoms recur across them), but
            # for what a kept precondition excludes already: false before the action in a state that
            # keeps the rules (every state these rows reach from one that does), and not added, so
            # false after it too (board's exclusions in zenotravel are all of this kind)
            if self._excluder is None:
                self._excluder = Excluder(self.domain, self.reached)
            held = [c for c in conds if c.value is True]
            beyond = [self._excluder.beyond(e, held) for e in adds]  # (keyed rules: no sets made)
            if all(b is not None for b in beyond):
                for xs in beyond:
                    for x in xs or ():
                        if x in index:
                            d_ids.add(index[x])
                        if x in negs:
                            a_ids.add(index[x.negate()])
            else:
                held_gone: set[int] = set()
                held_back: set[int] = set()
                for c in held:
                    gone, back = self._excluded(c)
                    held_gone |= gone
                    held_back |= back
                for e in adds:
                    gone, back = self._excluded(e)
                    d_ids |= gone - held_gone
                    a_ids |= back - held_back
            a_ids -= not_adds  # (an added atom is no exclusion: its "not" fact stays deleted)
        return p_ids, tuple(sorted(a_ids)), tuple(sorted(d_ids - a_ids))

    def _excluded(self, e: Atom) -> tuple[frozenset[int], frozenset[int]]:
        hit = self._excluded_ids.get(e)
        if hit is None:
            if self._excluder is None:
                self._excluder = Excluder(self.domain, self.reached)
            index, negs = self.index, self.negs
            out = self._excluder([e])
            hit = self._excluded_ids[e] = (frozenset(index[x] for x in out if x in index),
                                           frozenset(index[x.negate()] for x in out if x in negs))
        return hit


def _axiom_names(domain: Domain) -> frozenset[str]:
    return frozenset(ax.name for ax in domain.axioms)


def _ground_axioms(domain: Domain, rules: list[tuple[Action, list[Atom]]], index: Mapping[Atom, int],
                   negs: set[Atom]) -> GroundAxioms:
    """The ground rules as fact ids, sorted by stratum, and the derived facts they recompute."""
    strata = sorted(set(domain.derived.values()))
    layer_of = {p: strata.index(s) for p, s in domain.derived.items()}
    entries: list[tuple[int, tuple[int, ...], int]] = []
    for act, conds in rules:
        (head,) = act.effects()
        body = tuple(sorted({index[c] for c in conds}))
        entries.append((layer_of[head.predicate], body, index[head]))
    entries.sort(key=lambda e: e[0])  # stable: the rules keep their order within a layer
    layers = []
    for i in range(len(strata)):
        lo = next((k for k, e in enumerate(entries) if e[0] >= i), len(entries))
        hi = next((k for k, e in enumerate(entries) if e[0] > i), len(entries))
        layers.append((lo, hi))
    derived = {i for a, i in index.items() if a.value is True and a.predicate in domain.derived}
    negs_of: list[list[tuple[int, int]]] = [[] for _ in strata]
    for d in sorted(negs, key=_atom_order):
        if d.predicate in domain.derived and d in index:  # a derived atom never reached: "not d" always holds
            nd = index[d.negate()]
            derived.add(nd)
            negs_of[layer_of[d.predicate]].append((index[d], nd))
    return GroundAxioms(tuple(e[1] for e in entries), tuple(e[2] for e in entries), tuple(layers),
                        tuple(tuple(n) for n in negs_of), frozenset(derived))


def _atom_order(a: Atom) -> tuple[str, str, bool]:
    return (a.predicate, repr(a.args), bool(a.value))
