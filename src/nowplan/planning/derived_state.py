"""The derived facts of a :class:`State`: what the executive's world and belief keep after every action.

A domain with derived predicates evaluated by rules (``Domain.axioms``,
:mod:`nowplan.io.pddl_axioms`) never sets a derived atom by an action: the
atom is true exactly where its rules derive it from the basic facts.  The
forward search recomputes them in its integer states (:mod:`nowplan.planning.axioms`);
:class:`DerivedClosure` does the same for the executive's states, with the
same ground rules and evaluator, so that the simulated world, the belief,
goal tests and the checks of pre-images read a derived atom as the planner
does.  ``closure(state)`` drops the state's derived atoms and adds those the
rules derive from its other facts (stratum by stratum, each to its least
fixpoint).

The ground rules are those of the planner's task for the problem's objects,
grounded by relaxed reachability from a state (cached like every grounding);
a state with a changing fact that grounding never reached (an exogenous change)
is grounded again from it.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import flat_levels
from nowplan.core.state import State
from nowplan.planning.axioms import AxiomEvaluator, evaluator


class DerivedClosure:
    """``closure(state) -> state``: ``state``'s basic facts with the derived atoms its rules make true."""

    def __init__(self, domain: Domain, objects: Mapping[str, str | None]) -> None:
        self.domain = domain
        self.objects = dict(objects)
        self.derived = frozenset(domain.derived)
        self.statics = domain.static_predicates
        self._facts: list[Atom] = []
        self._index: dict[Atom, int] = {}
        self._negs: list[tuple[int, Atom]] = []  # ("not a" fact id, a)
        self._ev: AxiomEvaluator | None = None

    def _ground(self, state: State) -> None:
        from nowplan.planning.task import build_task

        task = build_task(self.domain, self.objects, state, Goal.of([], self.domain.rules), flat_levels(),
                          lambda _act: 0.0)
        self._facts, self._index = task.facts, task.index
        self._negs = [(i, a.negate()) for i, a in enumerate(task.facts) if a.value is False]
        self._ev = evaluator(task)

    def __call__(self, state: State) -> State:
        if not self.domain.axioms:
            return state
        derived = self.derived
        base = [a for a in state.atoms() if a.predicate not in derived]
        if self._ev is None or any(a not in self._index and a.predicate not in self.statics for a in base):
            self._ground(state)
        ev, index = self._ev, self._index
        assert ev is not None
        true = {a for a in base if a.value is True}
        ids = {index[a] for a in true if a in index}
        ids.update(i for i, pos in self._negs if pos not in true)  # (the evaluator recomputes the derived ones)
        facts = self._facts
        now = {facts[i] for i in ev.evaluate(ids)}
        made = {a for a in now if a.value is True and a.predicate in derived}
        old = {a for a in state.atoms() if a.predicate in derived}
        if made == old:
            return state
        return state.apply([*(a.negate() for a in old - made), *sorted(made - old, key=str)])


Pattern = tuple[str, tuple[object, ...]]  # a predicate with constants or WILD in its arguments
WILD = object()  # any object


class DerivedCones:
    """Which basic atoms a ground derived atom can depend on (its *cone*), as patterns from the lifted rules.

    Backward from the atom through the rules: a rule whose head matches gives
    its body's atoms, each argument the head's binding, a constant, or any
    object (an existential variable); a derived body atom is followed in turn.
    The patterns are finitely many (their constants come from the atom and the
    rules), so the walk ends.  An action none of whose effects matches the cone
    of ``d`` leaves ``d``'s truth as it was: :func:`nowplan.planning.forward.regress_actions`
    keeps ``d`` in the pre-image before such an action.
    """

    def __init__(self, domain: Domain) -> None:
        self.domain = domain
        self.statics = domain.static_predicates
        self._cones: dict[Pattern, frozenset[Pattern]] = {}

    def cone(self, atom: Atom) -> frozenset[Pattern]:
        key: Pattern = (atom.predicate, tuple(atom.args))
        hit = self._cones.get(key)
        if hit is None:
            hit = self._cones[key] = self._walk(key)
        return hit

    def _walk(self, start: Pattern) -> frozenset[Pattern]:
        from nowplan.core.atoms import Var

        derived, statics = self.domain.derived, self.statics
        seen, todo, base = {start}, [start], set()
        while todo:
            pred, args = todo.pop()
            for rule in self.domain.axioms:
                head = rule.effects[0]
                if head.predicate != pred:
                    continue
                bind: dict[object, object] = {}
                ok = True
                for h, v in zip(head.args, args, strict=True):
                    if isinstance(h, Var):
                        prev = bind.get(h)
                        bind[h] = v if prev is None or prev == v else WILD  # (bound twice, differently: any)
                    elif v is not WILD and h != v:
                        ok = False
                        break
                if not ok:
                    continue
                for p in rule.preconditions:
                    q = p.atom.predicate
                    if q in statics or q not in self.domain.predicates:
                        continue
                    pat: Pattern = (q, tuple(bind.get(a, WILD) if isinstance(a, Var) else a for a in p.atom.args))
                    if q in derived:
                        if pat not in seen:
                            seen.add(pat)
                            todo.append(pat)
                    else:
                        base.add(pat)
        return frozenset(base)

    def touches(self, effects: list[Atom], atom: Atom) -> bool:
        """Whether one of ``effects`` (ground atoms) may change the truth of the ground derived ``atom``."""
        cone = self.cone(atom)
        for e in effects:
            for pred, args in cone:
                if pred == e.predicate and all(a is WILD or a == b for a, b in zip(args, e.args, strict=True)):
                    return True
        return False


def derived_cones(domain: Domain) -> DerivedCones:
    """The domain's :class:`DerivedCones` (made once per domain)."""
    store = domain.facts.derived
    hit = store.get("derived cones")
    if not isinstance(hit, DerivedCones) or hit.domain is not domain:
        hit = store["derived cones"] = DerivedCones(domain)
    return hit


def derived_closure(domain: Domain, objects: Mapping[str, str | None]) -> DerivedClosure | None:
    """The :class:`DerivedClosure` of ``domain`` over ``objects`` (made once per domain and objects), or
    ``None`` for a domain without rules: what the executive's own projections of states (the monitor's
    expected states) apply after each action's effects."""
    if not domain.axioms:
        return None
    store: dict[Any, DerivedClosure] = domain.facts.derived.setdefault("derived closures", {})
    key = tuple(sorted(objects.items()))
    hit = store.get(key)
    if hit is None or hit.domain is not domain:
        hit = store[key] = DerivedClosure(domain, objects)
    return hit
