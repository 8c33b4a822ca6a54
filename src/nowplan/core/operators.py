"""Operator schemas and their ground instances (actions).

An :class:`Operator` has parameters, preconditions each with an integer
*criticality* (seed 002 II-B), results (effects), a cost (a number or a
function of the bindings and belief), declared *resources* with their kind of
use (seed 002 III-C) and *generators* that bind "choose" variables given the
goal, the belief and a planning context (seed 000: the plan stack, for
foresight).  :class:`Action` is a ground instance.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Hashable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Bindings, Term, Var, fmt_term, substitute

if TYPE_CHECKING:
    from nowplan.core.atoms import Goal


class ResourceUse(enum.Enum):
    """How achieving a subgoal uses a resource (seed 002 III-C)."""

    SHAREABLE = "shareable"  # stays available while used
    CONTAINED = "contained"  # unavailable while the goal is being achieved, then free
    CONTINUAL = "continual"  # unavailable for as long as the goal holds


@dataclass(frozen=True)
class Resource:
    """A resource template, e.g. ``Resource(("truck", Var("t")), ResourceUse.SHAREABLE)``."""

    name: tuple[Term, ...]
    use: ResourceUse = ResourceUse.CONTAINED

    def bind(self, b: Bindings) -> Resource:
        return Resource(tuple(substitute(t, b) for t in self.name), self.use)


@dataclass(frozen=True)
class Precondition:
    """A precondition and its criticality (higher: considered at more abstract levels).

    ``static=True`` (write it :func:`static`) marks a precondition on a
    predicate no operator changes: it needs no criticality of its own, since
    it is checked when the operator is grounded, at every level; the operator
    gives it its highest criticality so it adds no abstraction level.
    """

    atom: Atom
    criticality: int = 0
    static: bool = False


def static(a: Atom) -> Precondition:
    """A static precondition (e.g. ``static(atom("connects", d, r1, r2))``): no criticality needed."""
    return Precondition(a, 0, static=True)


GeneratorFn = Callable[..., Iterable[Mapping[Var, Any]]]
ReadsFn = Callable[[Mapping[Var, Any], "Goal"], Hashable]


@dataclass(frozen=True)
class Generator:
    """Binds ``outputs`` given the bindings so far, the goal, the belief and a context.

    ``fn(bindings, goal, belief, context)`` yields mappings from output
    variables to values, best first.  ``context`` is a
    :class:`nowplan.planning.context.PlanningContext` (or ``None``).
    """

    name: str
    outputs: tuple[Var, ...]
    fn: GeneratorFn = field(compare=False, hash=False)
    inputs: tuple[Var, ...] = ()
    # optional: ``reads(bindings, goal) -> key``, all the values depend on besides the bindings of
    # ``inputs``, the belief and the context; a planner may then keep the values per key
    # (``reads_nothing``: they do not depend on the goal, so a planner may rely on them everywhere)
    reads: ReadsFn | None = field(default=None, compare=False, hash=False)


def reads_nothing(bindings: Mapping[Var, Any], goal: Any) -> tuple[()]:
    """``Generator.reads`` for a generator whose values do not depend on the goal at all."""
    return ()


CostFn = Callable[[Bindings, Any], float]


class StateFreeCost:
    """A cost function of an action's arguments (and fixed data) alone, never of the belief.

    Subclass it (and implement ``__call__(bindings, belief)``) so that planners
    may compute each ground action's cost once per problem instead of once per
    call; a plain callable is assumed to read the belief.
    """

    def __call__(self, bindings: Bindings, belief: Any = None) -> float:
        raise NotImplementedError


@dataclass(frozen=True)
class Operator:
    """An operator schema: parameters, preconditions (each with a criticality), effects, cost.

    ``cost`` is a number or ``fn(bindings, belief)``; ``param_types`` name each
    parameter's type; ``resources`` are what achieving it uses (the peephole);
    ``generators`` bind parameters that no precondition or effect fixes.
    """

    name: str
    params: tuple[Var, ...]
    preconditions: tuple[Precondition, ...] = ()
    effects: tuple[Atom, ...] = ()
    cost: float | CostFn = field(default=1.0, compare=False, hash=False)
    param_types: tuple[str | None, ...] = ()
    resources: tuple[Resource, ...] = ()
    generators: tuple[Generator, ...] = ()
    # the name plans print (a PDDL action compiled into several operators prints its own name);
    # None: ``name``; "": an auxiliary operator that plans do not print (e.g. reaching a disjunctive goal)
    pddl_name: str | None = field(default=None, compare=False, hash=False)

    def __post_init__(self) -> None:
        if self.param_types and len(self.param_types) != len(self.params):
            raise ValueError(f"operator {self.name}: param_types and params differ in length")
        if any(p.static for p in self.preconditions):
            top = max((p.criticality for p in self.preconditions if not p.static), default=0)
            pres = tuple(Precondition(p.atom, top, True) if p.static else p for p in self.preconditions)
            object.__setattr__(self, "preconditions", pres)

    @property
    def criticalities(self) -> tuple[int, ...]:
        return tuple(sorted({p.criticality for p in self.preconditions}, reverse=True))

    def type_of(self, v: Var) -> str | None:
        if not self.param_types:
            return None
        return self.param_types[self.params.index(v)]

    def instantiate(self, bindings: Bindings) -> Action:
        missing = [v for v in self.params if v not in bindings]
        if missing:
            raise ValueError(f"operator {self.name}: unbound parameters {missing}")
        return Action(self, tuple(bindings[v] for v in self.params))


@dataclass(frozen=True, eq=False)
class Action:
    """A ground operator instance.  Equality is by name and arguments.

    Its ground preconditions (per level) and effects are computed once and
    kept (the instance is immutable; planners ask for them at every node).
    """

    operator: Operator
    args: tuple[Term, ...]
    _ground: dict[Any, tuple[Atom, ...]] = field(
        default_factory=dict, init=False, repr=False, compare=False, hash=False
    )
    # what planners derive from the instance and keep (e.g. its facts' ids per level)
    memo: dict[Any, Any] = field(default_factory=dict, init=False, repr=False, compare=False, hash=False)
    # (name, args): the instance's identity, made once (planners look actions up by it at every node)
    key: tuple[str, tuple[Term, ...]] = field(init=False, repr=False, compare=False, hash=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "key", (self.operator.name, self.args))

    @property
    def name(self) -> str:
        return self.operator.name

    @property
    def bindings(self) -> dict[Var, Term]:
        return dict(zip(self.operator.params, self.args, strict=True))

    def preconditions(self, level: int | None = None) -> tuple[Atom, ...]:
        """Ground preconditions of ``abs(op, level)``: criticality > level (all if None)."""
        out = self._ground.get(level)
        if out is None:
            if level is None:
                b = self.bindings
                out = tuple(p.atom.bind(b) for p in self.operator.preconditions)
            else:  # a level's are the full list's of criticality > level, made ground once
                full = self.preconditions(None)
                out = tuple(a for a, p in zip(full, self.operator.preconditions, strict=True) if p.criticality > level)
            self._ground[level] = out
        return out

    def effects(self) -> tuple[Atom, ...]:
        out = self._ground.get("effects")
        if out is None:
            b = self.bindings
            out = self._ground["effects"] = tuple(e.bind(b) for e in self.operator.effects)
        return out

    def cost(self, belief: Any = None) -> float:
        c = self.operator.cost
        return float(c(self.bindings, belief)) if callable(c) else float(c)

    @property
    def cost_is_state_free(self) -> bool:
        """The cost is a number or a :class:`StateFreeCost`: the same in every belief."""
        c = self.operator.cost
        return not callable(c) or isinstance(c, StateFreeCost)

    def resources(self) -> tuple[Resource, ...]:
        b = self.bindings
        return tuple(r.bind(b) for r in self.operator.resources)

    def is_primitive(self, level: int) -> bool:
        """At ``level`` every precondition is kept, so this instance is concrete."""
        return all(p.criticality > level for p in self.operator.preconditions)

    def pddl(self) -> str:
        """The action as PDDL, e.g. ``(move a b)``; "" for an auxiliary operator (see Operator.pddl_name)."""
        name = self.operator.pddl_name
        if name == "":
            return ""
        return "(" + " ".join([name or self.name, *(fmt_term(a) for a in self.args)]) + ")"

    def __str__(self) -> str:
        return f"{self.name}({', '.join(fmt_term(a) for a in self.args)})"

    def __hash__(self) -> int:
        return hash(self.key)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Action) and self.key == other.key


