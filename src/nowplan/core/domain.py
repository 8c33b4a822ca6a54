"""Predicates with test functions, domains and problems.

A :class:`Predicate` may carry a *test*: a function deciding whether an atom
holds in a state or belief, so the initial state never has to be listed in
full (seed 002 II-A).  Without a test, the belief must answer
``belief.value(key)`` (as :class:`nowplan.core.state.State` does) and the
predicate's value rule decides entailment.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import EQUALITY, Atom, AtMostOne, ConflictRule, Goal, Rules, Term, ValueRule, Var
from nowplan.core.facts import FactTable
from nowplan.core.operators import Operator
from nowplan.core.state import State
from nowplan.errors import ModelError

if TYPE_CHECKING:
    from nowplan.acting.monitor_support import MonitorSupport
    from nowplan.acting.resources import ResourceModel

TestFn = Callable[[Any, tuple[Term, ...], Any], bool]


@dataclass(frozen=True)
class Predicate:
    """A fluent's name, arity and argument types (``None``: any object).

    ``rule`` decides entailment between values of one fluent (default equality;
    :class:`~nowplan.core.atoms.ToleranceRule` for tolerances); ``test``, if
    given, decides truth from the belief (``test(belief, args, value)``)
    instead of looking the fluent up; ``boolean=False`` for valued fluents.
    """

    name: str
    arity: int
    arg_types: tuple[str | None, ...] = ()
    rule: ValueRule = field(default=EQUALITY, compare=False, hash=False)
    test: TestFn | None = field(default=None, compare=False, hash=False)
    boolean: bool = True


@dataclass(frozen=True)
class Domain:
    """The agent's model: predicates, operators, types, and what the engine asks of a domain.

    ``conflicts`` are rules saying which atoms never hold together
    (:func:`~nowplan.core.atoms.at_most_one`, :func:`~nowplan.core.atoms.exactly_one`,
    :func:`~nowplan.core.atoms.excludes`); ``triggers`` are reconsideration tests
    ``fn(plan, belief) -> reason | None``; ``planner`` the domain's own planner
    (the ``domain-planner`` switch); ``unsupported`` the strategy switches it
    refuses, with why; ``resources`` its :class:`~nowplan.acting.resources.ResourceModel`;
    ``monitor`` its :class:`~nowplan.acting.monitor_support.MonitorSupport`.
    Construction checks every operator's atoms against the predicates.
    """

    name: str
    predicates: Mapping[str, Predicate] = field(hash=False)
    operators: tuple[Operator, ...] = ()
    types: Mapping[str, str | None] = field(default_factory=dict, hash=False)
    constants: Mapping[str, str | None] = field(default_factory=dict, hash=False)
    conflicts: tuple[ConflictRule, ...] = field(default=(), hash=False, compare=False)
    # reconsideration triggers (seed 000 Fig. 5): fn(plan, belief) -> reason to replan, or None
    triggers: tuple[Callable[[Any, Any], str | None], ...] = field(default=(), hash=False, compare=False)
    # the domain's own planner, used by the executive under the ``domain-planner`` switch; it has
    # the signature of nowplan.planning.regression.plan and returns a PlanResult
    planner: Callable[..., Any] | None = field(default=None, hash=False, compare=False)
    # a cheap proof that no plan reaches a goal at a level map from the belief:
    # fn(goal, belief, levels, objects) -> why, or None (no proof); the regression planner asks it
    # before searching and answers "unsolvable" with the reason.  It must answer only where the
    # search itself would find no plan (e.g. an atom every achiever of which needs a fact that no
    # operator sequence from the belief can make true at that level).
    dead_end: Callable[[Any, Any, Any, Mapping[str, str | None]], str | None] | None = field(
        default=None, hash=False, compare=False)
    # strategy switches that cannot work on this domain, each with the reason and what to use
    # instead; a strategy naming one is refused before the run starts
    unsupported: Mapping[str, str] = field(default_factory=dict, hash=False, compare=False)
    # how the declared resources are estimated and shared (the peephole's ordering; default:
    # the declared uses at order 0)
    resources: ResourceModel | None = field(default=None, hash=False, compare=False)
    # what the expected-vs-observed monitor needs (distance between states, an own planner,
    # plan adaptation, body predicates; default: the number of differing fluents)
    monitor: MonitorSupport | None = field(default=None, hash=False, compare=False)
    # rules of derived predicates (PDDL axioms) evaluated after every action, stratum by stratum:
    # each an operator of cost 0 whose only effect is the derived atom (nowplan.io.pddl_axioms);
    # ``derived`` maps each derived predicate to its stratum.  Only the forward engine plans with them.
    axioms: tuple[Operator, ...] = ()
    derived: Mapping[str, int] = field(default_factory=dict, hash=False, compare=False)

    def __post_init__(self) -> None:
        for ax in self.axioms:
            if len(ax.effects) != 1 or ax.effects[0].predicate not in self.derived:
                raise ModelError(f"domain {self.name}: the axiom {ax.name} must have one effect, an atom of a "
                                 "derived predicate")
            for p in ax.preconditions:
                self.check_atom(p.atom, where=f"condition of axiom {ax.name}")
        names = [o.name for o in self.operators]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise ModelError(f"domain {self.name}: operator names repeated: {sorted(dup)}")
        changed = {e.predicate for o in self.operators for e in o.effects} | set(self.derived)
        for op in self.operators:
            for p in op.preconditions:
                self.check_atom(p.atom, where=f"precondition of operator {op.name}")
                if p.static and p.atom.predicate in changed:
                    raise ModelError(
                        f"operator {op.name}: static({p.atom}) but an operator changes "
                        f"'{p.atom.predicate}'; give it a criticality (Precondition(atom, n)) instead"
                    )
            for e in op.effects:
                self.check_atom(e, where=f"effect of operator {op.name}")
            unknown = {
                a
                for p in op.preconditions
                for a in p.atom.args
                if isinstance(a, Var) and a not in op.params
            } | {a for e in op.effects for a in e.args if isinstance(a, Var) and a not in op.params}
            if unknown:
                raise ModelError(
                    f"operator {op.name}: variables {sorted(str(v) for v in unknown)} are not "
                    "parameters; declare them in params"
                )

    # -- derived -------------------------------------------------------------
    @cached_property
    def rules(self) -> Rules:
        return Rules({n: p.rule for n, p in self.predicates.items()}, tuple(self.conflicts))

    @cached_property
    def facts(self) -> FactTable:
        """This domain's atoms interned as integers (see :mod:`nowplan.core.facts`)."""
        return FactTable(self.rules)

    @cached_property
    def operator_map(self) -> dict[str, Operator]:
        return {o.name: o for o in self.operators}

    @cached_property
    def max_criticality(self) -> int:
        crits = [p.criticality for o in self.operators for p in o.preconditions]
        return max(crits, default=0)

    @cached_property
    def min_criticality(self) -> float:
        """The lowest precondition criticality (``inf`` with no preconditions): below it all is concrete."""
        crits = [p.criticality for o in self.operators for p in o.preconditions]
        return min(crits, default=float("inf"))

    @cached_property
    def top_level(self) -> int:
        """The most abstract level: only preconditions of maximal criticality are kept."""
        return self.max_criticality - 1

    @cached_property
    def static_predicates(self) -> frozenset[str]:
        """Predicates no operator changes: their preconditions are checked at grounding."""
        changed = {e.predicate for o in self.operators for e in o.effects} | set(self.derived)
        return frozenset(n for n in self.predicates if n not in changed)

    def subtypes(self, t: str | None) -> set[str | None]:
        if t is None:
            return {None, *self.types}
        out: set[str | None] = {t}
        grew = True
        while grew:
            grew = False
            for child, parent in self.types.items():
                if parent in out and child not in out:
                    out.add(child)
                    grew = True
        return out

    # -- checks --------------------------------------------------------------
    def check_atom(self, a: Atom, where: str = "") -> None:
        pred = self.predicates.get(a.predicate)
        loc = f" ({where})" if where else ""
        if pred is None:
            known = ", ".join(sorted(self.predicates)) or "none"
            raise ModelError(f"unknown predicate '{a.predicate}'{loc}; known predicates: {known}")
        if len(a.args) != pred.arity:
            raise ModelError(
                f"predicate '{a.predicate}' takes {pred.arity} argument(s), "
                f"got {len(a.args)} in {a}{loc}"
            )

    # -- truth ---------------------------------------------------------------
    def holds(self, a: Atom, belief: Any) -> bool:
        """Does ``a`` hold in the state or belief (via the predicate's test)?"""
        pred = self.predicates.get(a.predicate)
        if pred is not None and pred.test is not None:
            return bool(pred.test(belief, a.args, a.value))
        have = belief.value(a.key)
        rule = pred.rule if pred is not None else EQUALITY
        if a.value is False:
            return have is False or have is None
        return have is not None and have is not False and rule.entails(have, a.value)

    @cached_property
    def plain_truth(self) -> bool:
        """No predicate has a test and every value rule is plain equality (PDDL domains): an atom asking
        a fluent to be true holds in a :class:`State` exactly when the state maps its key to true."""
        return all(p.test is None and type(p.rule) is ValueRule for p in self.predicates.values())

    def count_holding(self, belief: Any, atoms: Iterable[Atom]) -> int:
        """How many of ``atoms`` hold in the state or belief (the progress guard's measure of the goal)."""
        if self.plain_truth and isinstance(belief, State):  # one dictionary lookup per atom
            return belief.count_holding(atoms)
        return sum(self.holds(a, belief) for a in atoms)

    def unmet(self, belief: Any, atoms: Iterable[Atom]) -> list[Atom]:
        """The atoms that do not hold in the state or belief, in their order."""
        if self.plain_truth and isinstance(belief, State):  # one dictionary lookup per atom
            return belief.unmet(atoms)
        return [a for a in atoms if not self.holds(a, belief)]

    def satisfies(self, belief: Any, goal: Goal | Iterable[Atom]) -> bool:
        atoms = goal.atoms if isinstance(goal, Goal) else goal
        if self.plain_truth and isinstance(belief, State):  # one dictionary lookup per atom
            return belief.all_hold(atoms)
        return all(self.holds(a, belief) for a in atoms)


@dataclass(frozen=True)
class Problem:
    """Objects (name -> type), an initial state or belief, and a goal."""

    domain: Domain = field(hash=False)
    objects: Mapping[str, str | None] = field(hash=False)
    init: Any = field(hash=False, compare=False)
    goal: Goal
    name: str = "problem"
    # subgoals the executive achieves in this order before ``goal`` (each kept by the next, e.g. the
    # goal's literals of the most abstract level first); empty: plan for ``goal`` directly
    stages: tuple[Goal, ...] = field(default=(), compare=False)

    def __post_init__(self) -> None:
        for a in self.goal.atoms:
            self.domain.check_atom(a, where=f"goal of {self.name}")
        if isinstance(self.init, State):
            check_groups(self, self.init)

    @cached_property
    def all_objects(self) -> dict[str, str | None]:
        return {**dict(self.domain.constants), **dict(self.objects)}

    def objects_of(self, t: str | None) -> list[str]:
        if t is None:
            return sorted(self.all_objects)
        ok = self.domain.subtypes(t)
        return sorted(o for o, ot in self.all_objects.items() if ot in ok)


def check_groups(problem: Problem, state: State) -> None:
    """The state obeys the domain's ``at_most_one``/``exactly_one`` rules, else a ModelError naming the group."""
    dom = problem.domain
    for rule in dom.conflicts:
        if not isinstance(rule, AtMostOne):
            continue
        seen: dict[Any, Atom] = {}
        for pred in rule.predicates:
            for args in state.facts(pred):
                a = Atom(pred, tuple(args))
                g = rule.key_of(a)
                if g is None:
                    continue
                if g in seen:
                    raise ModelError(
                        f"{problem.name}: the initial state has {seen[g]} and {a}, but the domain's "
                        f"{rule} allows one; fix the initial state or the rule"
                    )
                seen[g] = a
        if rule.at_least_one:
            for g in _listable_groups(rule, problem):
                if g not in seen:
                    raise ModelError(
                        f"{problem.name}: the initial state has no {' or '.join(rule.predicates)} atom for "
                        f"{g!r}, but the domain's {rule} asks for one; add it to the initial state"
                    )


def _listable_groups(rule: AtMostOne, problem: Problem) -> list[Any]:
    if rule.key == ():
        return [()]
    if not isinstance(rule.key, int):
        return []
    types = {
        p.arg_types[rule.key]
        for name in rule.predicates
        if (p := problem.domain.predicates.get(name)) is not None and len(p.arg_types) > rule.key
    }
    if len(types) != 1 or None in types:
        return []
    (t,) = types
    return list(problem.objects_of(t))
