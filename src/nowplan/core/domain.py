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
from typing import Any

from nowplan.core.atoms import EQUALITY, Atom, ConflictRule, Goal, Rules, Term, ValueRule, Var
from nowplan.core.facts import FactTable
from nowplan.core.operators import Operator
from nowplan.errors import ModelError

TestFn = Callable[[Any, tuple[Term, ...], Any], bool]


@dataclass(frozen=True)
class Predicate:
    name: str
    arity: int
    arg_types: tuple[str | None, ...] = ()
    rule: ValueRule = field(default=EQUALITY, compare=False, hash=False)
    test: TestFn | None = field(default=None, compare=False, hash=False)
    boolean: bool = True


@dataclass(frozen=True)
class Domain:
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
    # strategy switches that cannot work on this domain, each with the reason and what to use
    # instead; a strategy naming one is refused before the run starts
    unsupported: Mapping[str, str] = field(default_factory=dict, hash=False, compare=False)

    def __post_init__(self) -> None:
        names = [o.name for o in self.operators]
        dup = {n for n in names if names.count(n) > 1}
        if dup:
            raise ModelError(f"domain {self.name}: operator names repeated: {sorted(dup)}")
        for op in self.operators:
            for p in op.preconditions:
                self.check_atom(p.atom, where=f"precondition of operator {op.name}")
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
        changed = {e.predicate for o in self.operators for e in o.effects}
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

    def satisfies(self, belief: Any, goal: Goal | Iterable[Atom]) -> bool:
        atoms = goal.atoms if isinstance(goal, Goal) else goal
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

    @cached_property
    def all_objects(self) -> dict[str, str | None]:
        return {**dict(self.domain.constants), **dict(self.objects)}

    def objects_of(self, t: str | None) -> list[str]:
        if t is None:
            return sorted(self.all_objects)
        ok = self.domain.subtypes(t)
        return sorted(o for o, ot in self.all_objects.items() if ot in ok)
