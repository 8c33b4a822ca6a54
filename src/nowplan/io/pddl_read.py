"""Read a STRIPS PDDL domain and problem into nowplan's core model.

The maintained ``pddl`` parser does the syntax; this module translates the
result into :class:`nowplan.core.domain.Domain` / :class:`Problem` and checks
what the parser does not (declared predicates, arities, known objects).

Supported fragment: ``:strips``, ``:typing``, ``:negative-preconditions``,
``:equality`` and ``:action-costs`` with constant ``(increase (total-cost) N)``
effects.  Negative goals are allowed.  Anything else (conditional effects,
quantifiers, disjunctions, derived predicates, numeric fluents, ...) raises
:class:`nowplan.errors.UnsupportedPDDLError`.

Modelling choices:

* equality is the static predicate ``=`` and the initial state lists
  ``=(o, o)`` for every object and constant: the grounder then joins and
  checks equalities like any static precondition (they never enter a
  pre-image) and relaxed heuristics see them as ordinary facts;
* effects are stored deletes first, then adds, so that applying them in
  order (``State.apply``) gives PDDL's "add wins" semantics;
* without a criticality file every precondition has criticality 1, so the
  domain is flat (``top_level`` 0: every instance is primitive);
* names are lower-cased (PDDL is case-insensitive).
"""

from __future__ import annotations

import logging
import re
from collections.abc import Iterable, Mapping
from dataclasses import replace
from pathlib import Path
from typing import Any

from nowplan.core.atoms import Atom, Goal, Term, Var
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.errors import ContradictoryGoalError, PDDLError
from nowplan.io.pddl_source import Source, parse_source, read_source

log = logging.getLogger(__name__)

EQUALITY = "="
SUPPORTED_REQUIREMENTS = ("strips", "typing", "negative-preconditions", "equality", "action-costs")
_FRAGMENT = "outside the supported STRIPS fragment (" + ", ".join(
    ":" + r for r in SUPPORTED_REQUIREMENTS
) + ")"


def equality_predicate() -> Predicate:
    """``=`` as a static predicate; its facts ``=(o, o)`` are added to the initial state."""
    return Predicate(EQUALITY, 2, (None, None))


def equality_facts(objects: Iterable[str]) -> list[Atom]:
    return [Atom(EQUALITY, (o, o)) for o in sorted(objects)]


# --------------------------------------------------------------------------- formulas


def _name(x: Any) -> str:
    return str(x).lower()


def _type_of(tags: Iterable[Any], src: Source, what: str) -> str | None:
    tags = sorted(_name(t) for t in tags)
    if not tags:
        return None
    if len(tags) > 1:
        raise src.error(
            f"{what} has an (either ...) type {tags}, which is {_FRAGMENT}",
            src.line_of(r"\(\s*either[\s)]"),
            unsupported=True,
        )
    return None if tags[0] == "object" else tags[0]


def _term(t: Any) -> Term:
    from pddl.logic.terms import Variable

    return Var(_name(t.name)) if isinstance(t, Variable) else _name(t.name)


_CONSTRUCTS = {
    "Or": "a disjunction (or ...)",
    "Imply": "an implication (imply ...)",
    "ForallCondition": "a universal quantifier (forall ...)",
    "ExistsCondition": "an existential quantifier (exists ...)",
    "When": "a conditional effect (when ...)",
    "Forall": "a universally quantified effect (forall ...)",
    "OneOf": "a non-deterministic effect (oneof ...)",
    "DerivedPredicate": "a derived predicate",
}


def _construct(f: Any) -> str:
    cls = type(f).__name__
    if cls in _CONSTRUCTS:
        return _CONSTRUCTS[cls]
    mod = type(f).__module__
    if mod.endswith("functions"):
        return f"a numeric expression ({f})"
    return f"the construct {f}"


def _unsupported(src: Source, f: Any, where: str, start: int) -> PDDLError:
    keyword = {
        "Or": "or", "Imply": "imply", "ForallCondition": "forall", "ExistsCondition": "exists",
        "When": "when", "Forall": "forall", "OneOf": "oneof",
    }.get(type(f).__name__)
    line = src.line_of_atom(keyword, start) if keyword else None
    return src.error(f"{where} uses {_construct(f)}, which is {_FRAGMENT}", line, unsupported=True)


def _literals(f: Any, src: Source, where: str, start: int) -> list[Atom]:
    """A conjunction of literals (atoms, negated atoms, equalities) as atoms."""
    from pddl.logic.base import And, Not
    from pddl.logic.predicates import EqualTo
    from pddl.logic.predicates import Predicate as PPred

    if f is None:
        return []
    if isinstance(f, And):
        return [a for op in f.operands for a in _literals(op, src, where, start)]
    value = True
    if isinstance(f, Not):
        value, f = False, f.argument
    if isinstance(f, PPred):
        return [Atom(_name(f.name), tuple(_term(t) for t in f.terms), value)]
    if isinstance(f, EqualTo):
        return [Atom(EQUALITY, (_term(f.left), _term(f.right)), value)]
    if type(f).__name__ == "Or" and not getattr(f, "operands", True):
        return []  # the parser's encoding of an empty precondition "()"
    raise _unsupported(src, f, where, start)


def _effects(f: Any, src: Source, where: str, start: int) -> tuple[list[Atom], float | None]:
    """Literal effects and the constant ``total-cost`` increase (or None)."""
    from pddl.logic.base import And
    from pddl.logic.functions import Increase, NumericFunction, NumericValue

    if f is None:
        return [], None
    parts = list(f.operands) if isinstance(f, And) else [f]
    atoms: list[Atom] = []
    cost: float | None = None
    for p in parts:
        if isinstance(p, Increase):
            fn, amount = p.operands
            if (
                isinstance(fn, NumericFunction)
                and _name(fn.name) == "total-cost"
                and isinstance(amount, NumericValue)
                and cost is None
            ):
                cost = float(amount.value)
                if cost < 0:
                    raise src.error(f"{where}: action costs must be >= 0, got {cost:g}",
                                    src.line_of(r"total-cost", start))
                continue
            raise src.error(
                f"{where} uses the numeric effect {p}; only a constant "
                f"(increase (total-cost) N) is supported, anything else is {_FRAGMENT}",
                src.line_of(r"\(\s*increase[\s(]", start),
                unsupported=True,
            )
        atoms.extend(_literals(p, src, where, start))
    return atoms, cost


# --------------------------------------------------------------------------- domain


def _check_atom(
    a: Atom,
    predicates: Mapping[str, Predicate],
    src: Source,
    where: str,
    start: int,
    variables: Iterable[Var] | None = None,
    objects: Mapping[str, str | None] | None = None,
) -> None:
    pred = predicates.get(a.predicate)
    if pred is None:
        known = ", ".join(sorted(p for p in predicates if p != EQUALITY)) or "none"
        raise src.error(
            f"unknown predicate '{a.predicate}' in {where}; declared predicates: {known}",
            src.line_of_atom(a.predicate, start),
        )
    if len(a.args) != pred.arity:
        raise src.error(
            f"predicate '{a.predicate}' takes {pred.arity} argument(s) but {where} gives "
            f"{len(a.args)} in {_show(a)}",
            src.line_of_atom(a.predicate, start),
        )
    for t in a.args:
        if isinstance(t, Var):
            if variables is not None and t not in variables:
                raise src.error(
                    f"{where} uses the variable ?{t.name}, which is not a parameter",
                    src.line_of_token("?" + t.name, start),
                )
        elif objects is not None and t not in objects:
            raise src.error(
                f"unknown object '{t}' in {where} ({_show(a)}); declare it in (:objects ...)",
                src.line_of_token(str(t), start),
            )


def _show(a: Atom) -> str:
    body = "(" + " ".join([a.predicate, *(str(t) if not isinstance(t, Var) else f"?{t.name}" for t in a.args)]) + ")"
    return body if a.value is not False else f"(not {body})"


def _check_requirements(reqs: Iterable[Any], src: Source) -> set[str]:
    names = {_name(r.value if hasattr(r, "value") else r).lstrip(":") for r in reqs}
    for r in sorted(names):
        if r not in SUPPORTED_REQUIREMENTS:
            raise src.error(
                f"requirement :{r} is {_FRAGMENT}",
                src.line_of(r":" + re.escape(r) + r"(?![\w-])"),
                unsupported=True,
            )
    return names


def _ordered(items: Iterable[Any], src: Source, pattern: str) -> list[Any]:
    """Items (named) in the order they appear in the file, for deterministic models."""
    def pos(x: Any) -> tuple[int, str]:
        m = re.search(pattern.format(re.escape(_name(x.name))), src.code)
        return (m.start() if m else len(src.code), _name(x.name))

    return sorted(items, key=pos)


def _check_unique_actions(src: Source) -> None:
    """Two actions of one name (the parser would keep only one of them silently)."""
    seen: set[str] = set()
    for m in re.finditer(r"\(\s*:action\s+([^\s()]+)", src.code, flags=re.IGNORECASE):
        name = m.group(1).lower()
        if name in seen:
            raise src.error(f"the action '{name}' is defined twice; rename or remove one",
                            src.code.count("\n", 0, m.start()) + 1)
        seen.add(name)


def read_domain(domain_path: str | Path) -> Domain:
    """Read a PDDL domain file (flat: every precondition has criticality 1, no mutexes)."""
    src = read_source(domain_path)
    d = parse_source(src, "domain")
    _check_unique_actions(src)
    reqs = _check_requirements(d.requirements, src)
    if d.derived_predicates:
        raise src.error(f"derived predicates are {_FRAGMENT}", src.line_of(r"\(:derived"),
                        unsupported=True)
    for fn in d.functions:
        if _name(fn.name) != "total-cost":
            raise src.error(
                f"the numeric fluent ({fn.name}) is {_FRAGMENT}; only (total-cost) is supported",
                src.line_of(r"\(:functions"),
                unsupported=True,
            )
    types: dict[str, str | None] = {}
    for t, parent in d.types.items():
        if _name(t) == "object":
            continue
        types[_name(t)] = None if parent is None or _name(parent) == "object" else _name(parent)
    constants = {
        _name(c.name): _type_of(c.type_tags, src, f"constant {c.name}") for c in d.constants
    }
    predicates: dict[str, Predicate] = {}
    for p in _ordered(d.predicates, src, r"\(\s*{}[\s)]"):
        name = _name(p.name)
        predicates[name] = Predicate(
            name,
            len(p.terms),
            tuple(_type_of(t.type_tags, src, f"predicate {name}") for t in p.terms),
        )
    uses_eq = "equality" in reqs or re.search(r"\(\s*=\s*[?\w]", src.code) is not None
    if uses_eq:
        predicates[EQUALITY] = equality_predicate()
    operators: list[Operator] = []
    costs: list[float | None] = []
    for act in _ordered(d.actions, src, r"\(:action\s+{}[\s)]"):
        name = _name(act.name)
        start = src.offset_of(r"\(:action\s+" + re.escape(name) + r"[\s)]")
        where = f"action {name}"
        params = tuple(Var(_name(v.name)) for v in act.parameters)
        if len(set(params)) != len(params):
            raise src.error(f"{where} repeats a parameter name", src.line_of(r":parameters", start))
        ptypes = tuple(_type_of(v.type_tags, src, f"parameter ?{v.name} of {where}") for v in act.parameters)
        pre = _literals(act.precondition, src, f"the precondition of {where}", start)
        eff, cost = _effects(act.effect, src, f"the effect of {where}", start)
        for a in pre:
            _check_atom(a, predicates, src, f"the precondition of {where}", start, params, constants)
        for a in eff:
            if a.predicate == EQUALITY:
                raise src.error(f"{where} has an equality in its effect", src.line_of(r"\(\s*=", start))
            _check_atom(a, predicates, src, f"the effect of {where}", start, params, constants)
        costs.append(cost)
        effects = [a for a in eff if a.value is False] + [a for a in eff if a.value is not False]
        operators.append(
            Operator(
                name,
                params,
                tuple(Precondition(a, 1) for a in pre),
                tuple(effects),
                param_types=ptypes,
            )
        )
    # PDDL :action-costs semantics: once costs are used, an action without an increase costs 0
    default = 0.0 if any(c is not None for c in costs) else 1.0
    operators = [
        replace(op, cost=c if c is not None else default) for op, c in zip(operators, costs, strict=True)
    ]
    return Domain(_name(d.name), predicates, tuple(operators), types, constants)



# --------------------------------------------------------------------------- problem


def load_domain(domain_path: str | Path, criticality_path: str | Path | None = None) -> Domain:
    """Read a domain and apply an optional criticality file (no mutexes: they need an init)."""
    domain = read_domain(domain_path)
    if criticality_path is not None:
        from nowplan.io.criticality import apply_criticality

        domain = apply_criticality(domain, criticality_path)
    return domain


def load_pddl(
    domain_path: str | Path,
    problem_path: str | Path,
    criticality_path: str | Path | None = None,
    *,
    mutexes: bool = True,
) -> Problem:
    """Read a domain and a problem (and a criticality file) into a :class:`Problem`.

    With ``mutexes`` (the default) the STRIPS invariants of
    :mod:`nowplan.planning.invariants` that hold in the initial state are
    added to ``domain.conflicts``, so regression prunes impossible subgoals.
    """
    domain = load_domain(domain_path, criticality_path)
    src = read_source(problem_path)
    p = parse_source(src, "problem")
    _check_requirements(p.requirements or (), src)
    if _name(p.domain_name) != domain.name:
        log.warning("%s: problem is for domain '%s' but the domain file defines '%s'",
                    src.path, _name(p.domain_name), domain.name)
    objects: dict[str, str | None] = {}
    for o in sorted(p.objects, key=lambda c: _name(c.name)):
        t = _type_of(o.type_tags, src, f"object {o.name}")
        if t is not None and t not in domain.types:
            raise src.error(
                f"object '{_name(o.name)}' has the unknown type '{t}'; domain types: "
                f"{', '.join(sorted(domain.types)) or 'none'}",
                src.line_of_token(t, src.offset_of(r"\(:objects")),
            )
        objects[_name(o.name)] = t
    known = {**dict(domain.constants), **objects}
    init_start = src.offset_of(r"\(:init")
    init_atoms = _init_atoms(p.init, src, init_start)
    for a in init_atoms:
        _check_atom(a, domain.predicates, src, "the initial state", init_start, (), known)
        if a.predicate == EQUALITY:
            raise src.error("equalities cannot be listed in the initial state",
                            src.line_of(r"\(\s*=", init_start))
    positives = {a.key for a in init_atoms if a.value is True}
    for a in init_atoms:
        if a.value is False and a.key in positives:
            raise src.error(f"the initial state lists both {_show(a.negate())} and {_show(a)}",
                            src.line_of_atom(a.predicate, init_start))
    goal_start = src.offset_of(r"\(:goal")
    goal_atoms = _literals(p.goal, src, "the goal", goal_start)
    for a in goal_atoms:
        _check_atom(a, domain.predicates, src, "the goal", goal_start, (), known)
    if p.metric is not None:
        expr = " ".join(str(p.metric).split()).lower()
        if expr not in ("minimize (total-cost)", "(minimize (total-cost))"):
            raise src.error(f"the metric '{expr}' is {_FRAGMENT}; only (minimize (total-cost)) is "
                            "supported", src.line_of(r"\(:metric"), unsupported=True)
    init_true = [a for a in init_atoms if a.value is True]
    if EQUALITY in domain.predicates:
        init_true += equality_facts(known)
    init = State(init_true)
    if mutexes:
        from nowplan.planning.invariants import infer_mutexes, mutex_rule

        groups = infer_mutexes(domain, init)
        if groups:
            domain = replace(domain, conflicts=(*domain.conflicts, mutex_rule(groups)))
    try:
        goal = Goal.of(goal_atoms, domain.rules)
    except ContradictoryGoalError as exc:
        raise ContradictoryGoalError(f"{src.path}: {exc} (in the goal)") from exc
    return Problem(domain, objects, init, goal, _name(p.name))


def _init_atoms(init: Iterable[Any], src: Source, start: int) -> list[Atom]:
    from pddl.logic.functions import EqualTo as FEqualTo
    from pddl.logic.functions import NumericFunction

    atoms: list[Atom] = []
    for f in sorted(init, key=str):
        if isinstance(f, FEqualTo):
            fn = f.operands[0]
            if isinstance(fn, NumericFunction) and _name(fn.name) == "total-cost":
                continue
            raise src.error(f"the initial state sets the numeric fluent {fn}, which is {_FRAGMENT}",
                            src.line_of(r"\(\s*=", start), unsupported=True)
        atoms.extend(_literals(f, src, "the initial state", start))
    return atoms
