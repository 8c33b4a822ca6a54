"""Write a core-model domain and problem back to PDDL text.

:func:`domain_text` and :func:`problem_text` give PDDL that
:func:`nowplan.io.pddl_read.load_pddl` reads back to the same model
(criticalities go to a side file, see
:func:`nowplan.io.criticality.criticality_text`).  :func:`export_level`
writes the abstraction ``abs(op, level)`` of every operator (only
preconditions of criticality > ``level``, and static ones, which the
regression planner checks at every level), so a flat planner such as Fast
Downward can plan at an HPN level.

Only the STRIPS part of the model can be written: boolean atoms, constant
non-negative costs or costs read from static numeric functions (written
back with their values), no generators; anything else raises
:class:`nowplan.errors.ModelError`.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path
from typing import Any

from nowplan.core.atoms import Atom, Term, Var
from nowplan.belief.protocols import ListsFacts
from nowplan.core.domain import Domain, Problem
from nowplan.core.operators import Operator
from nowplan.errors import ModelError
from nowplan.io.pddl_cost import FunctionCost, functions_of, show_expr

EQUALITY = "="


def _term(t: Term) -> str:
    return f"?{t.name}" if isinstance(t, Var) else str(t)


def _atom(a: Atom) -> str:
    if not isinstance(a.value, bool):
        raise ModelError(f"cannot write the non-boolean atom {a} as PDDL")
    body = "(" + " ".join([a.predicate, *(_term(t) for t in a.args)]) + ")"
    return body if a.value else f"(not {body})"


def _conj(atoms: Iterable[Atom], indent: str) -> str:
    parts = [_atom(a) for a in atoms]
    if not parts:
        return "(and)"
    if len(parts) == 1:
        return parts[0]
    return "(and " + f"\n{indent}     ".join(parts) + ")"


def _typed(names: Iterable[tuple[str, str | None]], typed: bool) -> str:
    out = []
    for n, t in names:
        out.append(f"{n} - {t or 'object'}" if typed else n)
    return " ".join(out)


def _function_cost(op: Operator) -> FunctionCost | None:
    return op.cost if isinstance(op.cost, FunctionCost) else None


def _cost(op: Operator) -> float:
    if isinstance(op.cost, FunctionCost):
        raise ModelError(f"operator {op.name} has a cost read from numeric functions")
    if callable(op.cost):
        raise ModelError(f"operator {op.name} has a cost function; only constant costs can be written")
    c = float(op.cost)
    if c < 0:
        raise ModelError(f"operator {op.name} has a negative cost {c:g}")
    return c


def _num(x: float) -> str:
    return str(int(x)) if float(x).is_integer() else repr(float(x))


def uses_costs(domain: Domain) -> bool:
    return any(_function_cost(op) is not None or _cost(op) != 1.0 for op in domain.operators)


def _cost_functions(domain: Domain) -> dict[str, int]:
    """Numeric functions (name -> arity) that action costs read (written as static functions)."""
    out: dict[str, int] = {}
    for op in domain.operators:
        fc = _function_cost(op)
        if fc is not None:
            for x in fc.exprs:
                out.update(functions_of(x))
    return out


def _cost_effect(op: Operator) -> str:
    fc = _function_cost(op)
    if fc is None:
        return f"(increase (total-cost) {_num(_cost(op))})"
    amount = show_expr(fc.exprs[0]) if len(fc.exprs) == 1 else "(+ " + " ".join(show_expr(x) for x in fc.exprs) + ")"
    return f"(increase (total-cost) {amount})"


def domain_text(domain: Domain, level: int | None = None) -> str:
    """PDDL for ``domain``; with ``level`` only preconditions of criticality > level.

    Static preconditions (of predicates no operator changes) are kept at
    every level, as the regression planner checks them at every level when
    grounding (see :mod:`nowplan.planning.grounding`).
    """
    typed = bool(domain.types) or any(
        t is not None for p in domain.predicates.values() for t in p.arg_types
    ) or any(t is not None for o in domain.operators for t in o.param_types)
    costs = uses_costs(domain)
    reqs = [":strips"]
    if typed:
        reqs.append(":typing")
    negative = any(p.atom.value is False for o in domain.operators for p in o.preconditions)
    if negative:
        reqs.append(":negative-preconditions")
    if EQUALITY in domain.predicates:
        reqs.append(":equality")
    if costs:
        reqs.append(":action-costs")
    if domain.axioms:
        reqs.append(":derived-predicates")
        if not negative and any(p.atom.value is False for ax in domain.axioms for p in ax.preconditions):
            reqs.append(":negative-preconditions")
        if any(len(ax.params) > len(ax.effects[0].args) for ax in domain.axioms):
            reqs.append(":existential-preconditions")
    static = domain.static_predicates
    lines = [f"(define (domain {domain.name})", f"  (:requirements {' '.join(reqs)})"]
    if domain.types:
        lines.append("  (:types " + " ".join(
            f"{t} - {parent or 'object'}" for t, parent in domain.types.items()) + ")")
    if domain.constants:
        lines.append(f"  (:constants {_typed(domain.constants.items(), typed)})")
    preds = []
    for p in domain.predicates.values():
        if p.name == EQUALITY:
            continue
        if not p.boolean:
            raise ModelError(f"cannot write the non-boolean predicate {p.name} as PDDL")
        args = [(f"?x{i}", (p.arg_types[i] if i < len(p.arg_types) else None)) for i in range(p.arity)]
        inner = _typed(args, typed)
        preds.append(f"({p.name}{' ' + inner if inner else ''})")
    lines.append("  (:predicates " + "\n               ".join(preds) + ")")
    if costs:
        fns = "".join(f" ({f}{''.join(f' ?x{i}' for i in range(n))}) - number"
                      for f, n in sorted(_cost_functions(domain).items()))
        lines.append(f"  (:functions (total-cost) - number{fns})")
    lines.extend(_derived_text(domain, typed))
    for op in domain.operators:
        if op.generators:
            raise ModelError(f"operator {op.name} uses generators; it cannot be written as PDDL")
        types = op.param_types or tuple(None for _ in op.params)
        params = _typed(((f"?{v.name}", t) for v, t in zip(op.params, types, strict=True)), typed)
        pre = [
            p.atom
            for p in op.preconditions
            if level is None or p.criticality > level or p.atom.predicate in static
        ]
        eff = [_atom(e) for e in op.effects]
        if costs:
            eff.append(_cost_effect(op))
        lines.append(f"  (:action {op.name}")
        lines.append(f"    :parameters ({params})")
        lines.append(f"    :precondition {_conj(pre, '    ')}")
        effect = eff[0] if len(eff) == 1 else "(and " + "\n             ".join(eff) + ")"
        if not eff:
            effect = "(and)"
        lines.append(f"    :effect {effect})")
    lines.append(")")
    return "\n".join(lines) + "\n"


def _derived_text(domain: Domain, typed: bool) -> list[str]:
    """One ``(:derived ...)`` per rule of a recursive derived predicate; its other variables existential."""
    lines = []
    for ax in domain.axioms:
        head = ax.effects[0]
        types = dict(zip(ax.params, ax.param_types or tuple(None for _ in ax.params), strict=True))
        hv = [t for t in head.args if isinstance(t, Var)]
        if len(hv) != len(head.args) or len(set(hv)) != len(hv):
            raise ModelError(f"the axiom {ax.name} has a head {head} that is not distinct variables")
        shown = _typed(((f"?{v.name}", types[v]) for v in hv), typed)
        body = _conj((p.atom for p in ax.preconditions), "      ")
        extra = [v for v in ax.params if v not in hv]
        if extra:
            body = f"(exists ({_typed(((f'?{v.name}', types[v]) for v in extra), typed)}) {body})"
        lines.append(f"  (:derived ({head.predicate}{' ' + shown if shown else ''})")
        lines.append(f"      {body})")
    return lines


def _init_atoms(init: Any) -> list[Atom]:
    if not isinstance(init, ListsFacts):
        raise ModelError("the initial belief is not a symbolic State; it cannot be written as PDDL")
    atoms = [a for a in init.atoms() if a.predicate != EQUALITY]
    for a in atoms:
        if a.value is not True:
            raise ModelError(f"cannot write the non-boolean fact {a} as PDDL")
    return atoms


def problem_text(problem: Problem) -> str:
    domain = problem.domain
    typed = bool(domain.types)
    lines = [f"(define (problem {problem.name})", f"  (:domain {domain.name})"]
    objs = [(o, t) for o, t in sorted(problem.objects.items()) if o not in domain.constants]
    if objs:
        lines.append(f"  (:objects {_typed(objs, typed)})")
    init = [_atom(a) for a in _init_atoms(problem.init)]
    if uses_costs(domain):
        init.append("(= (total-cost) 0)")
        values: dict[tuple[str, tuple[str, ...]], float] = {}
        for op in domain.operators:
            fc = _function_cost(op)
            if fc is not None and fc.values is not None:
                values.update(fc.values)
        init.extend(f"(= ({' '.join((f, *args))}) {_num(v)})" for (f, args), v in sorted(values.items()))
    lines.append("  (:init " + "\n         ".join(init) + ")")
    lines.append(f"  (:goal {_conj(problem.goal, '        ')})")
    if uses_costs(domain):
        lines.append("  (:metric minimize (total-cost))")
    lines.append(")")
    return "\n".join(lines) + "\n"


def export_level(problem: Problem, level: int | None) -> tuple[str, str]:
    """``(domain text, problem text)`` of ``problem`` at abstraction ``level`` (None: all)."""
    return domain_text(problem.domain, level), problem_text(problem)


def write_pddl(
    problem: Problem, directory: str | Path, level: int | None = None, stem: str = ""
) -> tuple[Path, Path]:
    """Write ``domain.pddl`` and ``problem.pddl`` (at ``level``) into ``directory``."""
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    dom, prob = export_level(problem, level)
    dp, pp = d / f"{stem}domain.pddl", d / f"{stem}problem.pddl"
    dp.write_text(dom, encoding="utf-8")
    pp.write_text(prob, encoding="utf-8")
    return dp, pp
