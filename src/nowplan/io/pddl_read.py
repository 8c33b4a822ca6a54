"""Read a PDDL domain and problem into nowplan's core model.

nowplan's own front end (:mod:`nowplan.io.sexpr`, :mod:`nowplan.io.pddl_syntax`)
reads the text leniently, as planners do in practice (see docs/pddl.md):
keywords in any case, requirements used but not declared (a warning),
``(either ...)`` types, ``object`` in ``:types``, ``total-cost`` with or
without ``:action-costs``, action costs that are constants or expressions
over static numeric functions of the action's parameters (their values come
from the problem's ``(= (f a b) 5)``).  :mod:`nowplan.io.pddl_check` checks
names, arities and types; :mod:`nowplan.io.pddl_adl` compiles quantifiers,
disjunctions and conditional effects to STRIPS operators over the problem's
objects.  What stays outside (durative actions, numeric fluents that change,
derived predicates recursive through a negation, ...) raises :class:`nowplan.errors.UnsupportedPDDLError`
naming the construct and its line.

Modelling choices:

* equality is the static predicate ``=`` and the initial state lists
  ``=(o, o)`` for every object and constant;
* effects are stored deletes first, then adds (PDDL's "add wins" under
  ``State.apply``);
* an action compiled into several operators (a disjunctive precondition,
  conditional effects, an ``(either ...)`` parameter) gives operators named
  ``NAME-v1``, ``NAME-v2``, ...; each has ``pddl_name`` NAME, which plans print;
* a disjunctive goal becomes the auxiliary atom ``(goal-reached)`` with one
  auxiliary operator (cost 0, not printed in plans) per disjunct;
* without a criticality file every precondition has criticality 1 (flat);
* names are lower-cased (PDDL is case-insensitive).
"""

from __future__ import annotations

import logging
import math
from collections.abc import Iterable, Mapping
from dataclasses import replace
from pathlib import Path

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.errors import CompilationBoundError, ContradictoryGoalError, PDDLError, UnsupportedPDDLError
from nowplan.io import pddl_adl as adl
from nowplan.io.pddl_ast import TOTAL_COST, EAnd, Reader, Effect, EForall, ELit, EWhen, FAnd, FAtom, FNot, Formula
from nowplan.io.pddl_check import EQUALITY, Checker, warn_undeclared
from nowplan.io.pddl_predtypes import goal_predicate_types, predicate_types
from nowplan.io.pddl_actions import NeedsObjects, World, atom_of, compile_action, objects_of, static_value
from nowplan.io.pddl_axioms import Strata, compile_rules, static_oracle, stratify, with_auxiliaries
from nowplan.io.pddl_source import read_source
from nowplan.io.pddl_syntax import DomainDef, ProblemDef, parse_domain, parse_problem
from nowplan.io.sexpr import SList, Token

log = logging.getLogger(__name__)

GOAL_REACHED = "goal-reached"


def equality_predicate() -> Predicate:
    """``=`` as a static predicate; its facts ``=(o, o)`` are added to the initial state."""
    return Predicate(EQUALITY, 2, (None, None))


def equality_facts(objects: Iterable[str]) -> list[Atom]:
    return [Atom(EQUALITY, (o, o)) for o in sorted(objects)]


# --------------------------------------------------------------------------- domain


def _read_domain_def(path: str | Path) -> tuple[DomainDef, Checker]:
    src = read_source(path)
    d = predicate_types(parse_domain(src.text, src.path))
    checker = Checker(d)
    warn_undeclared(d)
    _check_derived(d, checker)
    seen: dict[str, int] = {}
    for act in d.actions:
        if act.name in seen:
            raise PDDLError(f"the action '{act.name}' is defined twice (first on line {seen[act.name]}); "
                            "rename or remove one", path=d.path, line=act.line)
        seen[act.name] = act.line
        names = [p.name for p in act.params]
        if len(set(names)) != len(names):
            raise PDDLError(f"action {act.name} repeats a parameter name", path=d.path, line=act.line)
        scope = checker.bind(act.params, {}, f"action {act.name}", d.path)
        checker.formula(act.precondition, f"the precondition of action {act.name}", scope, checker.constants,
                        d.path)
        checker.effect(act.effect, f"the effect of action {act.name}", scope, checker.constants, d.path)
    return with_auxiliaries(d), checker


def _check_derived(d: DomainDef, checker: Checker) -> None:
    """Derived predicates: declared, typed bodies, never in effects, stratifiable."""
    changed: set[str] = set()
    for act in d.actions:
        _changed(act.effect, changed)
    for dv in d.derived:
        where = f"the derived predicate {dv.pred}"
        if dv.pred not in d.predicates:
            raise PDDLError(f"{where} is not declared in (:predicates ...)", path=d.path, line=dv.line)
        if len(dv.params) != len(d.predicates[dv.pred][0]):
            raise PDDLError(f"{where} has {len(dv.params)} parameter(s) but is declared with "
                            f"{len(d.predicates[dv.pred][0])}", path=d.path, line=dv.line)
        if dv.pred in changed:
            raise PDDLError(f"{where} is changed by an action's effect; derived predicates cannot be",
                            path=d.path, line=dv.line)
        scope = checker.bind(dv.params, {}, where, d.path)
        checker.formula(dv.body, where, scope, checker.constants, d.path)
    stratify(d)  # refuses a recursion through a negation


def _preds(f: Formula) -> set[str]:
    if isinstance(f, FAtom):
        return {f.pred}
    if isinstance(f, FNot):
        return _preds(f.arg)
    body = getattr(f, "body", None)
    if body is not None:
        return _preds(body)
    return {p for x in getattr(f, "parts", ()) for p in _preds(x)}


def _derived_map(d: DomainDef) -> adl.Derived:
    """The definitions of the derived predicates that are substituted (none once one is recursive)."""
    native = stratify(d).native
    out: dict[str, list[tuple[tuple[str, ...], Formula]]] = {}
    for dv in d.derived:
        if dv.pred in native:
            continue
        out.setdefault(dv.pred, []).append((tuple(p.name for p in dv.params), dv.body))
    return out


def _changed(e: Effect | None, out: set[str]) -> None:
    if isinstance(e, ELit):
        out.add(e.atom.pred)
    elif isinstance(e, EAnd):
        for p in e.parts:
            _changed(p, out)
    elif isinstance(e, EWhen | EForall):
        _changed(e.effect, out)


def _uses_equality(f: Formula | Effect | None) -> bool:
    if isinstance(f, FAtom):
        return f.pred == EQUALITY
    if isinstance(f, FNot):
        return _uses_equality(f.arg)
    if f is None or isinstance(f, ELit):
        return False
    if isinstance(f, EWhen):
        return _uses_equality(f.cond) or _uses_equality(f.effect)
    if isinstance(f, EForall):
        return _uses_equality(f.effect)
    parts = getattr(f, "parts", None)
    if parts is not None:
        return any(_uses_equality(p) for p in parts)
    body = getattr(f, "body", None)
    return _uses_equality(body) if body is not None else False


def _compile_domain(d: DomainDef, checker: Checker, world: World | None) -> Domain:
    changed: set[str] = set()
    for act in d.actions:
        _changed(act.effect, changed)
    strata = stratify(d)
    static = frozenset(p for p in d.predicates if p not in changed and p not in strata.stratum)
    predicates: dict[str, Predicate] = {}
    for name, (args, _) in d.predicates.items():
        predicates[name] = Predicate(name, len(args), tuple(a.types[0] if len(a.types) == 1 else None
                                                           for a in args))
    if "equality" in d.requirements or any(_uses_equality(a.precondition) or _uses_equality(a.effect)
                                           for a in d.actions):
        predicates[EQUALITY] = equality_predicate()
    operators: list[Operator] = []
    costed: list[bool] = []
    substituted = _derived_map(d)
    axioms = _compile_axioms(d, checker, static, world, strata, substituted)
    oracle = None
    if strata.native and world is not None:
        oracle = static_oracle(d, strata, objects_of(checker, world), static_value(static, world))
    for act in d.actions:
        ops, has_cost = compile_action(act, d, checker, static, world, substituted, oracle)
        operators.extend(ops)
        costed.extend([has_cost] * len(ops))
    # PDDL :action-costs semantics: once costs are used, an action without an increase costs 0
    if any(costed):
        operators = [op if c else replace(op, cost=0.0) for op, c in zip(operators, costed, strict=True)]
    if EQUALITY not in predicates and any(p.atom.predicate == EQUALITY for op in operators
                                          for p in op.preconditions):
        predicates[EQUALITY] = equality_predicate()  # parameters pinned per binding (pddl_actions)
    taken = {a.name for a in d.actions}
    for op in operators:
        if op.pddl_name is not None and op.name in taken:
            raise PDDLError(f"the action '{op.pddl_name}' compiles to the operator '{op.name}', which is also an "
                            "action of the domain; rename that action", path=d.path)
    if EQUALITY not in predicates and any(p.atom.predicate == EQUALITY for ax in axioms for p in ax.preconditions):
        predicates[EQUALITY] = equality_predicate()
    derived = {p: strata.stratum[p] for p in sorted(strata.native)}
    return Domain(d.name, predicates, tuple(operators), dict(checker.parent), dict(checker.constants),
                  axioms=axioms, derived=derived)


def _compile_axioms(d: DomainDef, checker: Checker, static: frozenset[str], world: World | None,
                    strata: Strata, substituted: adl.Derived) -> tuple[Operator, ...]:
    """The rules of the recursive derived predicates (:mod:`nowplan.io.pddl_axioms`)."""
    if not strata.native:
        return ()

    def alternatives(types: tuple[str, ...]) -> list[str | None]:
        alts: list[str | None] = [t for t in types if not any(o != t and o in checker.ancestors(t) for o in types)]
        return alts or [None]

    try:
        return compile_rules(d, strata, objects_of(checker, world), static_value(static, world), substituted,
                             alternatives)
    except NeedsObjects:
        line = min(dv.line for dv in d.derived if dv.pred in strata.native)
        raise UnsupportedPDDLError("a derived predicate quantifies over objects (forall); quantifiers "
                                   "are compiled over a problem's objects: read the domain together with a "
                                   "problem (load_pddl)", path=d.path, line=line) from None


def read_domain(domain_path: str | Path) -> Domain:
    """Read a PDDL domain file (flat: every precondition has criticality 1, no mutexes).

    Quantifiers need a problem's objects: such a domain is read with :func:`load_pddl`.
    """
    d, checker = _read_domain_def(domain_path)
    return _compile_domain(d, checker, None)


def load_domain(domain_path: str | Path, criticality_path: str | Path | None = None) -> Domain:
    """Read a domain and apply an optional criticality file (no mutexes: they need an init)."""
    domain = read_domain(domain_path)
    if criticality_path is not None:
        from nowplan.io.criticality import apply_criticality

        domain = apply_criticality(domain, criticality_path)
    return domain


# --------------------------------------------------------------------------- problem


def _read_init(p: ProblemDef, d: DomainDef, checker: Checker, known: Mapping[str, str | None]
               ) -> tuple[list[Atom], dict[tuple[str, tuple[str, ...]], float]]:
    atoms: list[Atom] = []
    values: dict[tuple[str, tuple[str, ...]], float] = {}
    for item, line in p.init:
        if not isinstance(item, SList):
            raise PDDLError(f"expected a fact in parentheses in the initial state, got '{item}'", path=p.path,
                            line=line)
        head = item.head()
        if head == "=" and len(item) == 3 and isinstance(item.items[1], SList):
            fn = item.items[1]
            fname = fn.head()
            val = item.items[2]
            if fname == TOTAL_COST:
                continue
            if fname not in checker.functions:
                if fname and not any(isinstance(a, SList) for a in fn.items[1:]):
                    # as Fast Downward: a value for a function no action reads is dropped
                    log.warning("%s:%d: the initial state gives a value to '%s', which the domain neither declares "
                                "nor uses (ignored)", p.path, line, fname)
                    continue
                raise PDDLError(f"unknown function '{fname or fn}' in the initial state; declared functions: "
                                f"{', '.join(sorted(f for f in checker.functions if f != TOTAL_COST)) or 'none'}",
                                path=p.path, line=line)
            args = tuple(str(a) for a in fn.items[1:])
            if any(isinstance(a, SList) for a in fn.items[1:]) or len(args) != len(checker.functions[fname]):
                raise PDDLError(f"function '{fname}' takes {len(checker.functions[fname])} object argument(s), "
                                f"got {fn} in the initial state", path=p.path, line=line)
            checker.args(args, checker.functions[fname], fname, "the initial state", {}, known, p.path, line)
            try:
                number = float(val.text) if isinstance(val, Token) else None
            except ValueError:
                number = None
            if number is None or not math.isfinite(number):
                raise PDDLError(f"the value of {fn} in the initial state must be a finite number, got {val}",
                                path=p.path, line=line)
            if (fname, args) in values and values[(fname, args)] != number:
                raise PDDLError(f"the initial state gives {fn} two values", path=p.path, line=line)
            values[(fname, args)] = number
            continue
        value = True
        if head == "not" and len(item) == 2 and isinstance(item.items[1], SList):
            value, item = False, item.items[1]
            head = item.head()
        if head == "at" and len(item) == 3 and isinstance(item.items[1], Token) and \
                item.items[1].text.replace(".", "", 1).isdigit():
            raise UnsupportedPDDLError(f"the initial state has the timed initial literal {item}; timed initial "
                                       "literals are not supported", path=p.path, line=line)
        if head in ("and", "or", "not", "forall", "exists", "when"):
            raise PDDLError(f"the initial state lists facts, not ({head} ...)", path=p.path, line=line)
        fact = Reader(p.path).atom(item, "the initial state")
        if fact.pred == EQUALITY:
            raise PDDLError("equalities cannot be listed in the initial state", path=p.path, line=line)
        checker.atom(fact, "the initial state", {}, known, p.path)
        atoms.append(Atom(fact.pred, fact.args, value))
    positives = {a.key for a in atoms if a.value is True}
    for atom in atoms:
        if atom.value is False and atom.key in positives:
            raise PDDLError(f"the initial state lists both {atom.negate()} and its negation", path=p.path)
    return atoms, values


def _is_conjunction(f: Formula) -> bool:
    if isinstance(f, FAtom):
        return True
    if isinstance(f, FNot):
        return isinstance(f.arg, FAtom)
    return isinstance(f, FAnd) and all(_is_conjunction(x) for x in f.parts)


def _literals(f: Formula) -> list[Atom]:
    if isinstance(f, FAtom):
        return [Atom(f.pred, f.args)]
    if isinstance(f, FNot):
        return [a.negate() for a in _literals(f.arg)]
    assert isinstance(f, FAnd)
    return [a for x in f.parts for a in _literals(x)]


def _goal_operators(disjuncts: list[frozenset[adl.Lit]], taken: Iterable[str]) -> tuple[str, list[Operator]]:
    names = set(taken)
    pred = GOAL_REACHED
    while pred in names:
        pred += "_"
    ops = [Operator(f"{pred}-{i + 1}", (), tuple(Precondition(atom_of(lit), 1) for lit in sorted(d)),
                    (Atom(pred, ()),), cost=0.0, pddl_name="") for i, d in enumerate(disjuncts)]
    return pred, ops


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
    d, checker = _read_domain_def(domain_path)
    try:
        return _load_problem(d, checker, problem_path, criticality_path, mutexes)
    except CompilationBoundError as exc:
        if not d.derived or stratify(d).native:
            raise
        # substituting the derived predicates' definitions blew up a disjunctive normal form (IPC-2004
        # philosophers: a goal of seven derived atoms, each a disjunction): evaluate them by rules instead,
        # as for recursive ones, which keeps every derived atom a single fact
        log.info("%s; evaluating the derived predicates by rules instead of substituting them", exc)
        return _load_problem(with_auxiliaries(replace(d, native_axioms=True)), checker, problem_path,
                             criticality_path, mutexes)


def _load_problem(d: DomainDef, checker: Checker, problem_path: str | Path, criticality_path: str | Path | None,
                  mutexes: bool) -> Problem:
    src = read_source(problem_path)
    p = parse_problem(src.text, src.path)
    if p.domain_name and p.domain_name != d.name:
        log.warning("%s: problem is for domain '%s' but the domain file defines '%s'",
                    src.path, p.domain_name, d.name)
    objects = dict(sorted(checker.objects_from(p.objects, "object", p.path).items()))
    known = {**checker.constants, **objects}
    init_atoms, values = _read_init(p, d, checker, known)
    assert p.goal is not None
    p.goal = goal_predicate_types(d, p.goal)
    checker.formula(p.goal, "the goal", {}, known, p.path)
    if p.metric is not None:
        direction, expr = p.metric
        if direction == "minimize" and getattr(expr, "name", None) == "total-time" and not getattr(expr, "args", ()):
            # the IPC-2002 STRIPS problems (zenotravel, driverlog, depots ...): a sequential plan has no
            # makespan to optimise, so the metric is dropped (Fast Downward refuses these files)
            log.warning("%s:%d: (:metric minimize (total-time)) is ignored: nowplan plans sequentially (accepted)",
                        p.path, p.metric_line)
        elif direction != "minimize" or not (getattr(expr, "name", None) == TOTAL_COST
                                             and not getattr(expr, "args", ())):
            raise UnsupportedPDDLError(f"the metric ({direction} ...) is not supported; only (:metric minimize "
                                       "(total-cost)) is", path=p.path, line=p.metric_line)
    world = World(known, frozenset((a.predicate, tuple(str(t) for t in a.args)) for a in init_atoms if a.value),
                  values, p.path)
    domain = _compile_domain(d, checker, world)
    goal_atoms: list[Atom] | None = None
    if _is_conjunction(p.goal) and not (_preds(p.goal) & {EQUALITY, *(dv.pred for dv in d.derived)}):
        goal_atoms = _literals(p.goal)
    else:
        changed: set[str] = set()
        for act in d.actions:
            _changed(act.effect, changed)
        static = frozenset(x for x in d.predicates if x not in changed and x not in domain.derived)
        try:
            value = static_value(static, world)
            strata = stratify(d)
            if strata.native:
                value = static_oracle(d, strata, objects_of(checker, world), value)
            nnf = adl.to_nnf(p.goal, {}, objects_of(checker, world), value, derived=_derived_map(d))
            disjuncts = adl.dnf(nnf, "the goal")
        except adl.TooLarge as exc:
            raise CompilationBoundError(f"{exc}; it is not compiled", path=p.path, line=p.goal_line) from None
        if len(disjuncts) == 1:
            goal_atoms = [atom_of(lit) for lit in sorted(disjuncts[0])]
        else:
            pred, aux = _goal_operators(disjuncts, [*domain.predicates, *(o.name for o in domain.operators)])
            domain = replace(domain, predicates={**domain.predicates, pred: Predicate(pred, 0)},
                             operators=(*domain.operators, *aux))
            goal_atoms = [Atom(pred, ())]
            if not disjuncts:
                log.warning("%s:%d: the goal is false in every state (its static facts fail)", p.path, p.goal_line)
    # quantifiers compiled over the objects put problem objects into operators: they become constants
    # of this (problem-specific) domain, so the domain written back stands on its own
    used = {t for op in domain.operators for pre in op.preconditions for t in pre.atom.args
            if isinstance(t, str)} | {t for op in domain.operators for e in op.effects for t in e.args
                                      if isinstance(t, str)}
    moved = {o: objects.pop(o) for o in sorted(used) if o in objects}
    if moved:
        domain = replace(domain, constants={**domain.constants, **moved})
    if criticality_path is not None:
        from nowplan.io.criticality import apply_criticality

        domain = apply_criticality(domain, criticality_path)
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
    problem = Problem(domain, objects, init, goal, p.name)
    if criticality_path == "auto":
        from nowplan.planning.problem_hierarchy import checked_type_sets

        problem = checked_type_sets(problem)  # type predicates that this problem's objects share
    return problem
