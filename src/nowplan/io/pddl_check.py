"""Checks of a PDDL domain and problem: types, names, arities, requirements.

:class:`Checker` holds the domain's type tree, constants, predicates and
functions, and checks every atom of the action bodies, the initial state and
the goal: a known predicate with the right number of arguments, variables
that are in scope, known objects, and types that fit (an object whose type
is not the declared one or below it, or a variable whose type cannot
overlap the declared one, is an error naming the file, line and object).
:func:`used_requirements` finds what a domain uses, so an undeclared
requirement is a warning (as in Fast Downward) rather than an error.
"""

from __future__ import annotations

import logging
from collections.abc import Iterable, Mapping

from nowplan.errors import PDDLError, UnsupportedPDDLError
from nowplan.io.pddl_ast import (
    TOTAL_COST,
    EAnd,
    ECost,
    Effect,
    EForall,
    ELit,
    EWhen,
    FAnd,
    FAtom,
    FNot,
    FOr,
    Formula,
    FQuant,
    NExpr,
    NFunc,
    NOp,
    TypedName,
)
from nowplan.io.pddl_syntax import DomainDef

log = logging.getLogger(__name__)

EQUALITY = "="
KNOWN_REQUIREMENTS = frozenset({
    "strips", "typing", "negative-preconditions", "disjunctive-preconditions", "equality",
    "existential-preconditions", "universal-preconditions", "quantified-preconditions",
    "conditional-effects", "adl", "action-costs", "derived-predicates", "fluents", "numeric-fluents",
    "object-fluents", "durative-actions", "duration-inequalities", "continuous-effects",
    "timed-initial-literals", "preferences", "constraints", "non-deterministic",
})
# a requirement a construct needs, and the declared requirements that imply it
_IMPLIED = {
    "typing": {"typing", "adl"},
    "negative-preconditions": {"negative-preconditions", "adl"},
    "disjunctive-preconditions": {"disjunctive-preconditions", "adl"},
    "equality": {"equality", "adl"},
    "existential-preconditions": {"existential-preconditions", "quantified-preconditions", "adl"},
    "universal-preconditions": {"universal-preconditions", "quantified-preconditions", "adl"},
    "conditional-effects": {"conditional-effects", "adl"},
    "action-costs": {"action-costs", "numeric-fluents", "fluents"},
    "derived-predicates": {"derived-predicates"},
}

Scope = Mapping[str, tuple[str, ...]]  # variable -> its types (() = object)


class Checker:
    def __init__(self, d: DomainDef) -> None:
        self.path = d.path
        self.parent: dict[str, str | None] = {}
        for t, parents in d.types.items():
            if len(parents) > 1:
                raise UnsupportedPDDLError(f"the type '{t}' has the parent (either {' '.join(parents)}); "
                                           "a type with several parents is not supported",
                                           path=d.path, line=d.type_lines[t])
            self.parent[t] = parents[0] if parents else None
        for t, parent in list(self.parent.items()):
            if parent is not None and parent not in self.parent:
                self.parent[parent] = None  # declared only as a parent: a child of object
        for t in self.parent:
            seen = {t}
            p = self.parent[t]
            while p is not None:
                if p in seen:
                    raise PDDLError(f"the type '{t}' is its own ancestor (a cycle in :types)", path=d.path,
                                    line=d.type_lines.get(t))
                seen.add(p)
                p = self.parent[p]
        self.constants = self.objects_from(d.constants, "constant", d.path)
        self.predicates = {n: args for n, (args, _) in d.predicates.items()}
        self.functions = {n: args for n, (args, _) in d.functions.items()}
        for n, args in self.predicates.items():
            for a in args:
                self.check_types(a.types, d.path, a.line, f"the predicate {n}")

    # ------------------------------------------------------------------ types

    def check_types(self, types: tuple[str, ...], path: str, line: int, what: str) -> None:
        for t in types:
            if t not in self.parent:
                known = ", ".join(sorted(self.parent)) or "none (declare them in (:types ...))"
                raise PDDLError(f"unknown type '{t}' in {what}; declared types: {known}", path=path, line=line)

    def ancestors(self, t: str | None) -> list[str]:
        out = []
        while t is not None:
            out.append(t)
            t = self.parent.get(t)
        return out

    def is_a(self, t: str | None, of: tuple[str, ...]) -> bool:
        """An object of type ``t`` (None: object) fits ``of`` (() = object, several = either)."""
        return not of or any(a in of for a in self.ancestors(t))

    def overlaps(self, have: tuple[str, ...], want: tuple[str, ...]) -> bool:
        """Can a variable of types ``have`` take a value that fits ``want``?"""
        if not have or not want:
            return True
        return any(w in self.ancestors(h) or h in self.ancestors(w) for h in have for w in want)

    def objects_from(self, names: Iterable[TypedName], what: str, path: str) -> dict[str, str | None]:
        out: dict[str, str | None] = {}
        for o in names:
            if len(o.types) > 1:
                raise UnsupportedPDDLError(f"the {what} '{o.name}' has the type (either {' '.join(o.types)}); "
                                           "objects of several types are not supported", path=path, line=o.line)
            self.check_types(o.types, path, o.line, f"the {what} '{o.name}'")
            t = o.types[0] if o.types else None
            if o.name in out and out[o.name] != t:
                raise PDDLError(f"the {what} '{o.name}' is declared twice with different types", path=path,
                                line=o.line)
            if o.name in out:
                log.warning("%s:%d: the %s '%s' is declared twice", path, o.line, what, o.name)
            out[o.name] = t
        return out

    # ------------------------------------------------------------------ atoms

    def atom(self, a: FAtom, where: str, scope: Scope, objects: Mapping[str, str | None], path: str) -> None:
        if a.pred == EQUALITY:
            decl: tuple[TypedName, ...] | None = (TypedName("?a", (), 0), TypedName("?b", (), 0))
        else:
            decl = self.predicates.get(a.pred)
        if decl is None:
            known = ", ".join(sorted(self.predicates)) or "none"
            raise PDDLError(f"unknown predicate '{a.pred}' in {where}; declared predicates: {known}",
                            path=path, line=a.line)
        if len(a.args) != len(decl):
            shown = "(" + " ".join((a.pred, *a.args)) + ")"
            raise PDDLError(f"predicate '{a.pred}' takes {len(decl)} argument(s) but {where} gives "
                            f"{len(a.args)} in {shown}", path=path, line=a.line)
        self.args(a.args, decl, a.pred, where, scope, objects, path, a.line)

    def args(self, args: tuple[str, ...], decl: tuple[TypedName, ...], name: str, where: str, scope: Scope,
             objects: Mapping[str, str | None], path: str, line: int) -> None:
        for i, (arg, d) in enumerate(zip(args, decl, strict=True)):
            want = d.types
            if arg.startswith("?"):
                if arg not in scope:
                    raise PDDLError(f"{where} uses the variable {arg}, which is not a parameter or a "
                                    "quantified variable", path=path, line=line)
                if not self.overlaps(scope[arg], want):
                    raise PDDLError(f"the variable {arg} of type {_show(scope[arg])} cannot be argument {i + 1} "
                                    f"of '{name}' (type {_show(want)}) in {where}", path=path, line=line)
            else:
                if arg not in objects:
                    hint = "(:objects ...)" if where in ("the initial state", "the goal") else "(:constants ...)"
                    raise PDDLError(f"unknown object '{arg}' in {where}; declare it in {hint}", path=path,
                                    line=line)
                if not self.is_a(objects[arg], want):
                    raise PDDLError(f"the object '{arg}' of type {objects[arg] or 'object'} cannot be argument "
                                    f"{i + 1} of '{name}' (type {_show(want)}) in {where}", path=path, line=line)

    def formula(self, f: Formula | None, where: str, scope: Scope, objects: Mapping[str, str | None],
                path: str) -> None:
        if f is None:
            return
        if isinstance(f, FAtom):
            self.atom(f, where, scope, objects, path)
        elif isinstance(f, FNot):
            self.formula(f.arg, where, scope, objects, path)
        elif isinstance(f, FAnd | FOr):
            for p in f.parts:
                self.formula(p, where, scope, objects, path)
        else:
            assert isinstance(f, FQuant)
            self.formula(f.body, where, self.bind(f.params, scope, where, path), objects, path)

    def bind(self, params: Iterable[TypedName], scope: Scope, where: str, path: str) -> dict[str, tuple[str, ...]]:
        out = dict(scope)
        for p in params:
            self.check_types(p.types, path, p.line, f"the variable {p.name} of {where}")
            out[p.name] = p.types
        return out

    def effect(self, e: Effect | None, where: str, scope: Scope, objects: Mapping[str, str | None],
               path: str) -> None:
        if e is None:
            return
        if isinstance(e, ELit):
            self.atom(e.atom, where, scope, objects, path)
        elif isinstance(e, EAnd):
            for p in e.parts:
                self.effect(p, where, scope, objects, path)
        elif isinstance(e, EWhen):
            self.formula(e.cond, where, scope, objects, path)
            self.effect(e.effect, where, scope, objects, path)
        elif isinstance(e, EForall):
            self.effect(e.effect, where, self.bind(e.params, scope, where, path), objects, path)
        else:
            assert isinstance(e, ECost)
            self.numeric(e.amount, where, scope, objects, path, e.line)

    def numeric(self, x: NExpr, where: str, scope: Scope, objects: Mapping[str, str | None], path: str,
                line: int) -> None:
        if isinstance(x, NOp):
            for a in x.args:
                self.numeric(a, where, scope, objects, path, line)
        elif isinstance(x, NFunc):
            if x.name == TOTAL_COST:
                raise UnsupportedPDDLError(f"{where} has the numeric effect (increase (total-cost) ...(total-cost)...); "
                                           "action costs must not depend on the cost so far", path=path, line=x.line)
            decl = self.functions.get(x.name)
            if decl is None:
                # Fast Downward's translator takes a function it was never told of (the values come from
                # the problem's :init); declare it here, untyped, with the arity of this first use.
                log.warning("%s:%d: the function '%s' is used in %s but not declared in (:functions ...) "
                            "(accepted, untyped)", path, x.line, x.name, where)
                decl = tuple(TypedName(f"?x{i + 1}", (), x.line) for i in range(len(x.args)))
                self.functions[x.name] = decl
            if len(decl) != len(x.args):
                raise PDDLError(f"function '{x.name}' takes {len(decl)} argument(s) but {where} gives "
                                f"{len(x.args)}", path=path, line=x.line)
            self.args(x.args, decl, x.name, where, scope, objects, path, x.line)


def _show(types: tuple[str, ...]) -> str:
    if not types:
        return "object"
    return types[0] if len(types) == 1 else "(either " + " ".join(types) + ")"


# --------------------------------------------------------------------------- requirements


def _formula_uses(f: Formula | None, out: dict[str, int], positive: bool = True) -> None:
    if f is None:
        return
    if isinstance(f, FAtom):
        if f.pred == EQUALITY:
            out.setdefault("equality", f.line)
        if not positive:
            out.setdefault("negative-preconditions", f.line)
    elif isinstance(f, FNot):
        _formula_uses(f.arg, out, not positive)
    elif isinstance(f, FAnd | FOr):
        if isinstance(f, FOr) and len(f.parts) > 1:
            lines = [p.line for p in f.parts if isinstance(p, FAtom)]
            out.setdefault("disjunctive-preconditions", lines[0] if lines else 0)
        for p in f.parts:
            _formula_uses(p, out, positive)
    else:
        assert isinstance(f, FQuant)
        kind = "universal" if (f.kind == "forall") == positive else "existential"
        out.setdefault(f"{kind}-preconditions", f.line)
        _formula_uses(f.body, out, positive)


def _effect_uses(e: Effect | None, out: dict[str, int]) -> None:
    if isinstance(e, EAnd):
        for p in e.parts:
            _effect_uses(p, out)
    elif isinstance(e, EWhen):
        out.setdefault("conditional-effects", e.line)
        _formula_uses(e.cond, out)
        _effect_uses(e.effect, out)
    elif isinstance(e, EForall):
        out.setdefault("conditional-effects", e.line)
        _effect_uses(e.effect, out)
    elif isinstance(e, ECost):
        out.setdefault("action-costs", e.line)


def warn_undeclared(d: DomainDef) -> dict[str, int]:
    """Log a warning per requirement the domain uses without declaring it; return the uses."""
    for r, line in d.requirements.items():
        if r not in KNOWN_REQUIREMENTS:
            log.warning("%s:%d: unknown requirement :%s (ignored)", d.path, line, r)
    used: dict[str, int] = {}
    typed = [t.line for t in d.constants if t.types] + [
        a.line for args, _ in d.predicates.values() for a in args if a.types]
    if d.types or typed:
        used["typing"] = min(typed) if typed else min(d.type_lines.values(), default=d.line)
    for act in d.actions:
        _formula_uses(act.precondition, used)
        _effect_uses(act.effect, used)
    if d.derived:
        used["derived-predicates"] = d.derived[0].line
    declared = set(d.requirements)
    for r, line in sorted(used.items(), key=lambda x: x[1]):
        if not declared & _IMPLIED[r]:
            log.warning("%s:%d: the domain uses :%s without declaring it in (:requirements ...) (accepted)",
                        d.path, line, r)
    return used
