"""Unary predicates used as the type of a variable (the IPC-2000 full-ADL idiom).

The IPC-2000 elevator domain in its full-ADL version quantifies over
predicates as if they were types: ``(exists (?p - conflict_A) ...)``,
``(forall (?p - vip) (served ?p))``, where ``conflict_A`` and ``vip`` are
unary predicates, not declared types.  The intended reading (and the one the
competition's later "fixed" copies spell out) is a variable over the
predicate's argument type restricted to the objects of which the predicate
holds.  :func:`predicate_types` rewrites every such variable that way, with a
warning naming the file and line:

* in ``forall``: ``(forall (?p - T) (imply (vip ?p) body))`` with ``T`` the
  predicate's argument type;
* in ``exists``: ``(exists (?p - T) (and (vip ?p) body))``;
* in a ``forall`` effect: ``(forall (?p - T) (when (vip ?p) effect))``;
* in an action's or a derived predicate's parameters: ``(vip ?p)`` joins the
  precondition (the body).

Fast Downward's translator reads such a variable as ranging over the objects
of an undeclared type, that is over no object; the two readings agree on
problems where the predicate holds of no object.  A type name that is
neither a declared type nor a unary predicate stays an error (the checker's
"unknown type").
"""

from __future__ import annotations

import logging
from dataclasses import replace

from nowplan.io.pddl_ast import (
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
    TypedName,
)
from nowplan.io.pddl_syntax import DomainDef

log = logging.getLogger(__name__)


class _Rewriter:
    def __init__(self, d: DomainDef) -> None:
        self.path = d.path
        declared = set(d.types) | {p for ps in d.types.values() for p in ps} | {"object"}
        # a unary predicate whose name is not a type can stand for one
        self.unary = {n: args[0].types for n, (args, _) in d.predicates.items()
                      if len(args) == 1 and n not in declared}
        self.used: set[str] = set()

    def params(self, params: tuple[TypedName, ...]) -> tuple[tuple[TypedName, ...], tuple[FAtom, ...]]:
        """The parameters with predicate types replaced, and the atoms that restrict them."""
        out: list[TypedName] = []
        conds: list[FAtom] = []
        for p in params:
            if len(p.types) == 1 and p.types[0] in self.unary:
                pred = p.types[0]
                if pred not in self.used:
                    log.warning("%s:%d: the variable %s has the predicate '%s' as its type: read as (%s ?x) "
                                "holding of it (the IPC-2000 full-ADL idiom; Fast Downward reads it as an "
                                "empty type)", self.path, p.line, p.name, pred, pred)
                    self.used.add(pred)
                out.append(TypedName(p.name, self.unary[pred], p.line))
                conds.append(FAtom(pred, (p.name,), p.line))
            else:
                out.append(p)
        return tuple(out), tuple(conds)

    def formula(self, f: Formula) -> Formula:
        if isinstance(f, FAtom):
            return f
        if isinstance(f, FNot):
            return FNot(self.formula(f.arg))
        if isinstance(f, FAnd):
            return FAnd(tuple(self.formula(x) for x in f.parts))
        if isinstance(f, FOr):
            return FOr(tuple(self.formula(x) for x in f.parts))
        assert isinstance(f, FQuant)
        params, conds = self.params(f.params)
        body = self.formula(f.body)
        if conds:
            if f.kind == "forall":
                body = FOr((*(FNot(c) for c in conds), body))
            else:
                body = FAnd((*conds, body))
        return FQuant(f.kind, params, body, f.line)

    def effect(self, e: Effect) -> Effect:
        if isinstance(e, ELit | ECost):
            return e
        if isinstance(e, EAnd):
            return EAnd(tuple(self.effect(x) for x in e.parts))
        if isinstance(e, EWhen):
            return EWhen(self.formula(e.cond), self.effect(e.effect), e.line)
        assert isinstance(e, EForall)
        params, conds = self.params(e.params)
        inner = self.effect(e.effect)
        if conds:
            inner = EWhen(FAnd(conds), inner, e.line)
        return EForall(params, inner, e.line)


def _with(conds: tuple[FAtom, ...], f: Formula | None) -> Formula | None:
    if not conds:
        return f
    return FAnd((*conds, f)) if f is not None else FAnd(conds)


def predicate_types(d: DomainDef) -> DomainDef:
    """``d`` with every variable typed by a unary predicate rewritten (see the module text)."""
    r = _Rewriter(d)
    if not r.unary:
        return d
    actions = []
    for a in d.actions:
        params, conds = r.params(a.params)
        pre = _with(conds, r.formula(a.precondition) if a.precondition is not None else None)
        actions.append(replace(a, params=params, precondition=pre,
                               effect=r.effect(a.effect) if a.effect is not None else None))
    derived = []
    for dv in d.derived:
        params, conds = r.params(dv.params)
        body = _with(conds, r.formula(dv.body))
        assert body is not None
        derived.append(replace(dv, params=params, body=body))
    return replace(d, actions=actions, derived=derived)


def goal_predicate_types(d: DomainDef, goal: Formula) -> Formula:
    """The goal with quantified variables typed by unary predicates rewritten."""
    r = _Rewriter(d)
    return r.formula(goal) if r.unary else goal
