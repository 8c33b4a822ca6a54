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

from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom, Goal, KeyedRule, contradiction
from nowplan.belief.protocols import ListsFacts
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
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
    if not isinstance(belief, ListsFacts):
        return "the belief does not list its facts"
    if any(op.generators for op in domain.operators):
        return "operators have generators"
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


def build_task(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap,
    cost_of: Any,
) -> Task:
    """The integer task for ``goal`` from ``belief`` with each action at its level in ``levels``."""
    top = max([levels.top, *(lv for _, lv in levels.overrides)])
    gr = grounding(domain, objects, belief, top)
    statics = gr.statics
    facts: list[Atom] = []
    index: dict[Atom, int] = {}

    def fid(a: Atom) -> int:
        i = index.get(a)
        if i is None:
            i = index[a] = len(facts)
            facts.append(a)
        return i

    true_now = {a for a in belief.atoms() if a.value is True}
    negs: set[Atom] = set()  # the positive atoms whose negation is a condition somewhere
    kept = _reachable(gr, levels, statics, true_now)
    rules = [(act, conds) for act, conds in kept if act.operator.name in _axiom_names(domain)]
    if rules:
        kept = [(act, conds) for act, conds in kept if act.operator.name not in _axiom_names(domain)]
    for _, conds in kept + rules:
        negs.update(p.negate() for p in conds if p.value is False)
    negs.update(a.negate() for a in goal.atoms if a.value is False and a.predicate not in statics)
    # ids in a canonical order, whatever the cache saw before: the same call makes the same plan
    reached = set(true_now)
    for act, _ in kept + rules:
        reached.update(e for e in act.effects() if e.value is True)
    for a in sorted(reached, key=_atom_order):
        fid(a)
    for a in sorted(negs, key=_atom_order):
        fid(a.negate())
    abstract = any(not levels.is_primitive(act) for act, _ in kept)
    excludes = _Excluder(domain, reached) if abstract and domain.rules.conflicts else None
    pre: list[tuple[int, ...]] = []
    add: list[tuple[int, ...]] = []
    dele: list[tuple[int, ...]] = []
    cost: list[float] = []
    actions: list[Action] = []
    for act, conds in kept:
        p_ids = tuple(sorted({fid(c) if c.value is True else index[c] for c in conds}))
        adds = {e for e in act.effects() if e.value is True}
        dels = {e.negate() for e in act.effects() if e.value is False} - adds
        if excludes is not None and not levels.is_primitive(act):
            dels |= excludes(adds) - adds
        a_ids = {index[e] for e in adds if e in index}
        d_ids = {index[e] for e in dels if e in index}
        a_ids |= {index[e.negate()] for e in dels if e in negs}
        d_ids |= {index[e.negate()] for e in adds if e in negs}
        actions.append(act)
        pre.append(p_ids)
        add.append(tuple(sorted(a_ids)))
        dele.append(tuple(sorted(d_ids - a_ids)))
        cost.append(float(cost_of(act)))
    init = frozenset({index[a] for a in true_now if a in index}
                     | {index[n.negate()] for n in negs if n not in true_now})
    task = Task(facts, index, actions, pre, add, dele, cost, init, ())
    if domain.axioms:
        task.axioms = _ground_axioms(domain, rules, index, negs)
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
        i = index.get(a)
        if i is None:
            task.unsolvable = f"the goal needs {a}, which no action sequence reaches"
            continue
        goal_ids.append(i)
    task.goal = tuple(sorted(goal_ids))
    task.index_preconditions()
    keyed = [c for c in domain.rules.conflicts if isinstance(c, KeyedRule)]
    if keyed:
        task.memo["mutex"] = FactMutex(facts, keyed)
    return task


class FactMutex:
    """``mutex(f, g)``: the conflict rules (inferred invariants) exclude facts ``f`` and ``g`` together."""

    def __init__(self, facts: list[Atom], keyed: list[KeyedRule]) -> None:
        self._facts = facts
        self._keyed = keyed
        self._memo: dict[int, frozenset[Any]] = {}

    def keys(self, f: int) -> frozenset[Any]:
        """The (rule, group) pairs of fact ``f``: two facts sharing one are mutex."""
        hit = self._memo.get(f)
        if hit is None:
            a = self._facts[f]
            hit = self._memo[f] = frozenset((i, k) for i, r in enumerate(self._keyed) for k in r.group_keys(a)) \
                if a.value is True else frozenset()
        return hit

    def isolated(self, f: int) -> bool:
        """No fact is mutex with ``f`` (it is in no group)."""
        return not self.keys(f)

    def __call__(self, f: int, g: int) -> bool:
        return f != g and bool(self.keys(f) & self.keys(g))


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


def _reachable(gr: Grounding, levels: LevelMap, statics: frozenset[str],
               true_now: set[Atom]) -> list[tuple[Action, list[Atom]]]:
    """The actions a relaxed exploration from ``true_now`` reaches at their levels, in name order.

    Each comes with its conditions at its level (static ones left out: the
    grounding checked them).
    """
    conds_of: list[tuple[Action, list[Atom]]] = []
    waiting: dict[Atom, list[int]] = {}
    missing: list[int] = []
    for act in gr.actions:
        conds = [p for p in act.preconditions(levels.level(act)) if p.predicate not in statics]
        k = len(conds_of)
        conds_of.append((act, conds))
        need = {p for p in conds if p.value is True}
        missing.append(len(need))
        for p in need:
            waiting.setdefault(p, []).append(k)
    reached: set[Atom] = set()
    fired = [k for k, m in enumerate(missing) if m == 0]
    queue = list(true_now)
    for k in fired:
        queue.extend(e for e in conds_of[k][0].effects() if e.value is True)
    while queue:
        f = queue.pop()
        if f in reached:
            continue
        reached.add(f)
        for k in waiting.pop(f, ()):
            missing[k] -= 1
            if missing[k] == 0:
                fired.append(k)
                queue.extend(e for e in conds_of[k][0].effects() if e.value is True and e not in reached)
    out = [conds_of[k] for k in fired]
    out.sort(key=lambda ac: (ac[0].name, repr(ac[0].args)))
    return out


class _Excluder:
    """The reached atoms that the domain's conflict rules exclude once an atom is added."""

    def __init__(self, domain: Domain, reached: Iterable[Atom]) -> None:
        self.rules = domain.rules
        self.reached = sorted(reached)
        self.memo: dict[Atom, frozenset[Atom]] = {}
        keyed = [c for c in self.rules.conflicts if isinstance(c, KeyedRule)]
        self.plain = [c for c in self.rules.conflicts if not isinstance(c, KeyedRule)]
        self.groups: dict[Any, list[Atom]] = {}
        self.keyed = keyed
        for a in self.reached:
            for rule in keyed:
                for k in rule.group_keys(a):
                    self.groups.setdefault(k, []).append(a)

    def __call__(self, adds: Iterable[Atom]) -> set[Atom]:
        out: set[Atom] = set()
        for e in adds:
            hit = self.memo.get(e)
            if hit is None:
                found: set[Atom] = set()
                for rule in self.keyed:
                    for k in rule.group_keys(e):
                        found.update(x for x in self.groups.get(k, ()) if x != e)
                if self.plain:
                    found.update(x for x in self.reached
                                 if x != e and contradiction([e, x], self.rules, new=[x]) is not None)
                hit = self.memo[e] = frozenset(found)
            out |= hit
        return out
