"""Derived predicates (PDDL axioms): stratification, and the recursive ones compiled to rules.

A derived predicate ``p`` depends on the predicates its definitions mention,
positively or negatively (under an odd number of ``not``).  The strongly
connected components of this graph are the recursions; a set of axioms is
*stratifiable* when no recursion goes through a negation, and then each
derived predicate gets a *stratum*: at least the stratum of every derived
predicate it depends on positively, and one more than those it depends on
negatively.  Evaluating the strata in order, each to its least fixpoint,
gives the standard (stratified, closed-world) semantics of PDDL 2.2.

Non-recursive derived predicates are compiled away by substitution
(:mod:`nowplan.io.pddl_adl`); the recursive ones are compiled here into
*rules*: lifted operators whose only effect is the derived atom, cost 0,
one per disjunct of a definition's body in disjunctive normal form.
Existentially quantified variables at the top of a body (under ``and`` /
``or``) become parameters of the rule, as in Fast Downward's translator,
instead of being expanded over the objects.  The forward search evaluates
the ground rules after every action (:mod:`nowplan.planning.axioms`).
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace

from nowplan.core.atoms import Atom, Var
from nowplan.core.operators import Operator, Precondition
from nowplan.errors import UnsupportedPDDLError
from nowplan.io import pddl_adl as adl
from nowplan.io.pddl_ast import FAnd, FAtom, FNot, FOr, Formula, FQuant, TypedName
from nowplan.io.pddl_syntax import DerivedDef, DomainDef

AXIOM_CRITICALITY = 10**6  # a rule's conditions are kept at every level
AXIOM_PREFIX = "axiom:"  # rule operators are named axiom:PRED-N (not a PDDL name: never an action's)


@dataclass(frozen=True)
class Strata:
    """The derived predicates' strata and which of them are recursive."""

    stratum: Mapping[str, int]
    recursive: frozenset[str]
    forced: bool = False  # DomainDef.native_axioms: rules although nothing is recursive

    @property
    def native(self) -> frozenset[str]:
        """The derived predicates evaluated by rules: all of them once one is recursive (or forced), else none.

        Without recursion every derived atom is replaced by its definition
        (exact, and the regression planner and HPN can use the domain); with
        recursion the search evaluates rules anyway, and substituting the
        non-recursive ones into each other (PSR's ``fed`` over ``upstream``)
        can blow up the disjunctive normal forms.  ``forced`` is the same choice made
        for a problem whose substituted definitions exceed a bound (IPC-2004
        philosophers: the goal's seven ``blocked`` atoms, each a disjunction).
        """
        return frozenset(self.stratum) if self.recursive or self.forced else frozenset()


def polarities(f: Formula, positive: bool = True) -> set[tuple[str, bool]]:
    """The predicates of ``f`` with the sign they occur with (``False``: under a negation)."""
    if isinstance(f, FAtom):
        return {(f.pred, positive)}
    if isinstance(f, FNot):
        return polarities(f.arg, not positive)
    if isinstance(f, FAnd | FOr):
        return {x for p in f.parts for x in polarities(p, positive)}
    return polarities(f.body, positive)


def stratify(d: DomainDef) -> Strata:
    """Strata of the derived predicates; refuses a recursion through a negation, naming the predicate."""
    derived = {dv.pred for dv in d.derived}
    line = {dv.pred: dv.line for dv in reversed(d.derived)}
    edges: dict[str, set[tuple[str, bool]]] = {p: set() for p in derived}
    for dv in d.derived:
        edges[dv.pred] |= {(q, s) for q, s in polarities(dv.body) if q in derived}
    comp = _components(sorted(derived), {p: sorted({q for q, _ in es}) for p, es in edges.items()})
    recursive: set[str] = set()
    for p in sorted(derived):
        for q, positive in sorted(edges[p]):
            if comp[q] != comp[p]:
                continue
            recursive.add(p)
            if not positive:
                why = "in its own definition" if p == q else f"while {q} depends on {p}"
                raise UnsupportedPDDLError(
                    f"the derived predicates are not stratifiable: {p} depends on (not {q}) {why}; "
                    "negation is only allowed on a derived predicate of a lower stratum (define it without "
                    "the negated recursion)", path=d.path, line=line[p])
    # strata: longest path with a weight of 1 on negative edges, over the components (a DAG)
    stratum: dict[str, int] = {}

    def level(p: str, depth: int) -> int:  # depth-first; bounded by the number of predicates
        if p in stratum:
            return stratum[p]
        members = [x for x in derived if comp[x] == comp[p]]
        best = 0
        for x in members:
            for q, positive in edges[x]:
                if comp[q] != comp[p]:
                    best = max(best, level(q, depth + 1) + (0 if positive else 1))
        for x in members:
            stratum[x] = best
        return best

    for p in sorted(derived):
        level(p, 0)
    return Strata(stratum, frozenset(recursive), d.native_axioms)


def _components(nodes: list[str], succ: Mapping[str, list[str]]) -> dict[str, int]:
    """Tarjan's strongly connected components (iterative): node -> component id."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    comp: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    counter = 0
    for root in nodes:
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            v, i = work.pop()
            if i == 0:
                index[v] = low[v] = counter
                counter += 1
                stack.append(v)
                on.add(v)
            out = succ.get(v, [])
            if i < len(out):
                work.append((v, i + 1))
                w = out[i]
                if w not in index:
                    work.append((w, 0))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            if low[v] == index[v]:
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp[w] = index[v]
                    if w == v:
                        break
            if work:
                u = work[-1][0]
                low[u] = min(low[u], low[v])
    return comp


def with_auxiliaries(d: DomainDef) -> DomainDef:
    """``d`` with each universal condition of a natively evaluated derived predicate made an auxiliary one.

    ``(forall (?v) phi)`` in a definition (or ``(exists (?v) phi)`` under a
    negation) would put one conjunct per object into every disjunct of the
    disjunctive normal form (blocker's ``cat-moves``: 3**n disjuncts).  As
    Fast Downward's translator does, it becomes ``(not (AUX ?free))`` with the
    new derived predicate ``AUX(?free) = (exists (?v) (not phi))`` over its
    free variables: one stratum lower, evaluated by rules like the others.
    Domains without recursion (whose derived predicates are substituted) are
    returned as they are.
    """
    if not stratify(d).native:
        return d
    preds = dict(d.predicates)
    extra: list[DerivedDef] = []

    def fresh(base: str) -> str:
        k = 1
        while f"{base}-aux{k}" in preds:
            k += 1
        return f"{base}-aux{k}"

    def walk(f: Formula, positive: bool, scope: dict[str, TypedName], owner: DerivedDef) -> Formula:
        if isinstance(f, FAtom):
            return f
        if isinstance(f, FNot):
            return FNot(walk(f.arg, not positive, scope, owner))
        if isinstance(f, FAnd):
            return FAnd(tuple(walk(x, positive, scope, owner) for x in f.parts))
        if isinstance(f, FOr):
            return FOr(tuple(walk(x, positive, scope, owner) for x in f.parts))
        inner = {**scope, **{p.name: p for p in f.params}}
        universal = (f.kind == "forall") == positive
        if not universal:
            return FQuant(f.kind, f.params, walk(f.body, positive, inner, owner), f.line)
        free = sorted(v for v in _free(f) if v in scope)
        name = fresh(owner.pred)
        params = tuple(TypedName(v, scope[v].types, f.line) for v in free)
        preds[name] = (params, f.line)
        body: Formula = FQuant("exists", f.params, FNot(f.body), f.line) if f.kind == "forall" else f
        aux = DerivedDef(name, params, body, f.line)
        extra.append(DerivedDef(name, params, walk(body, True, {p.name: p for p in params}, aux), f.line))
        atom = FAtom(name, tuple(free), f.line)
        return FNot(atom) if f.kind == "forall" else atom

    native = stratify(d).native
    derived = []
    for dv in d.derived:
        if dv.pred in native:
            dv = DerivedDef(dv.pred, dv.params, walk(dv.body, True, {p.name: p for p in dv.params}, dv), dv.line)
        derived.append(dv)
    if not extra:
        return d
    return replace(d, predicates=preds, derived=[*derived, *extra])


def _free(f: Formula) -> set[str]:
    if isinstance(f, FAtom):
        return {a for a in f.args if a.startswith("?")}
    if isinstance(f, FNot):
        return _free(f.arg)
    if isinstance(f, FAnd | FOr):
        return {v for x in f.parts for v in _free(x)}
    return _free(f.body) - {p.name for p in f.params}


# --------------------------------------------------------------------------- rules


def _lift(f: Formula, taken: set[str]) -> list[tuple[list[TypedName], Formula, dict[str, str]]]:
    """``f`` as a disjunction of (new parameters, body, renaming): top-level ``exists`` lifted.

    The renaming maps each lifted variable to a fresh name (not in ``taken``).
    """
    if isinstance(f, FOr):
        return [r for p in f.parts for r in _lift(p, taken)]
    if isinstance(f, FQuant) and f.kind == "exists":
        fresh: dict[str, str] = {}
        params = []
        for p in f.params:
            n, k = p.name, 1
            while n in taken:
                k += 1
                n = f"{p.name}-{k}"
            taken.add(n)
            fresh[p.name] = n
            params.append(TypedName(n, p.types, p.line))
        return [([*params, *extra], body, {**fresh, **sub}) for extra, body, sub in _lift(f.body, taken)]
    if isinstance(f, FAnd):
        out: list[tuple[list[TypedName], Formula, dict[str, str]]] = [([], FAnd(()), {})]
        for part in f.parts:
            nxt: list[tuple[list[TypedName], Formula, dict[str, str]]] = []
            for (e1, b1, s1), (e2, b2, s2) in itertools.product(out, _lift(part, taken)):
                nxt.append(([*e1, *e2], FAnd((*_parts(b1), b2)), {**s1, **s2}))
            out = nxt
            if len(out) > adl.MAX_DISJUNCTS:
                raise adl.TooLarge(f"has more than {adl.MAX_DISJUNCTS} disjuncts")
        return out
    return [([], f, {})]


def _parts(f: Formula) -> tuple[Formula, ...]:
    return f.parts if isinstance(f, FAnd) else (f,)


def _rename(f: Formula, sub: Mapping[str, str]) -> Formula:
    """``f`` with the free occurrences of the variables in ``sub`` renamed."""
    if not sub:
        return f
    if isinstance(f, FAtom):
        return FAtom(f.pred, tuple(sub.get(a, a) for a in f.args), f.line)
    if isinstance(f, FNot):
        return FNot(_rename(f.arg, sub))
    if isinstance(f, FAnd):
        return FAnd(tuple(_rename(p, sub) for p in f.parts))
    if isinstance(f, FOr):
        return FOr(tuple(_rename(p, sub) for p in f.parts))
    inner = {k: v for k, v in sub.items() if k not in {p.name for p in f.params}}
    return FQuant(f.kind, f.params, _rename(f.body, inner), f.line)


def compile_rules(
    d: DomainDef,
    strata: Strata,
    objects_of: Callable[[tuple[str, ...]], Sequence[str]],
    static: adl.StaticValue,
    substituted: adl.Derived,
    type_alternatives: Callable[[tuple[str, ...]], list[str | None]],
) -> tuple[Operator, ...]:
    """The rules of the derived predicates evaluated natively, as operators ``axiom:PRED-N`` of cost 0."""
    out: list[Operator] = []
    count: dict[str, int] = {}
    for dv in d.derived:
        if dv.pred not in strata.native:
            continue
        where = f"the derived predicate {dv.pred}"
        head = Atom(dv.pred, tuple(Var(p.name[1:]) for p in dv.params))
        try:
            lifted = _lift(dv.body, {p.name for p in dv.params})
        except adl.TooLarge as exc:
            raise UnsupportedPDDLError(f"{where} {exc}; it is not compiled", path=d.path, line=dv.line) from None
        for extra, body, sub in lifted:
            params = (*dv.params, *extra)
            try:
                nnf = adl.to_nnf(_rename(body, sub), {}, objects_of, static, derived=substituted)
                disjuncts = adl.dnf(nnf, where)
            except adl.TooLarge as exc:
                raise UnsupportedPDDLError(f"{exc}; it is not compiled", path=d.path, line=dv.line) from None
            choices = [type_alternatives(p.types) for p in params]
            combos = list(itertools.islice(itertools.product(*choices), 65))
            if len(combos) > 64:
                raise UnsupportedPDDLError(f"{where} has (either ...) parameters with more than 64 combinations "
                                           "of types", path=d.path, line=dv.line)
            for disjunct, types in itertools.product(disjuncts, combos):
                count[dv.pred] = count.get(dv.pred, 0) + 1
                out.append(Operator(
                    f"{AXIOM_PREFIX}{dv.pred}-{count[dv.pred]}",
                    tuple(Var(p.name[1:]) for p in params),
                    tuple(Precondition(_atom(lit), AXIOM_CRITICALITY) for lit in sorted(disjunct)),
                    (head,),
                    cost=0.0,
                    param_types=tuple(types),
                    pddl_name="",
                ))
    return tuple(out)


def static_oracle(d: DomainDef, strata: Strata, objects_of: Callable[[tuple[str, ...]], Sequence[str]],
                  static: adl.StaticValue) -> adl.StaticValue:
    """``static`` extended to ground atoms of natively evaluated derived predicates that are always false.

    A ground derived atom is false in every state when each of its
    definitions is false on the static facts alone (derived atoms inside it
    taken as unknown): PSR's ``(affected ?b)`` needs ``(breaker ?b)``, so it
    is false for every switch, and the ``wait`` action's one conditional
    effect per device keeps only those of the breakers.  Anything else is
    unknown (``None``), as before.
    """
    defs: dict[str, list[tuple[tuple[str, ...], Formula]]] = {}
    for dv in d.derived:
        if dv.pred in strata.native:
            defs.setdefault(dv.pred, []).append((tuple(p.name for p in dv.params), dv.body))
    memo: dict[tuple[str, tuple[str, ...]], bool] = {}

    def plain(lit: adl.Lit) -> bool | None:
        return None if lit[0] in defs else static(lit)

    def value(lit: adl.Lit) -> bool | None:
        pred, args, v = lit
        if pred not in defs:
            return static(lit)
        if any(a.startswith("?") for a in args):
            return None
        key = (pred, args)
        if key not in memo:
            memo[key] = not any(maybe(body, dict(zip(params, args, strict=True)), True)
                                for params, body in defs[pred])
        return (not v) if memo[key] else None

    def maybe(f: Formula, sub: dict[str, str], positive: bool) -> bool:
        """Can ``f`` (negated unless ``positive``) hold, judged on the static facts only?"""
        if isinstance(f, FAtom):
            known = plain((f.pred, tuple(sub.get(a, a) for a in f.args), positive))
            return known is not False
        if isinstance(f, FNot):
            return maybe(f.arg, sub, not positive)
        if isinstance(f, FAnd | FOr):
            conj = isinstance(f, FAnd) == positive
            test = all if conj else any
            return test(maybe(x, sub, positive) for x in f.parts)
        conj = (f.kind == "forall") == positive
        pools = [objects_of(p.types) for p in f.params]
        test = all if conj else any
        return test(maybe(f.body, {**sub, **dict(zip((p.name for p in f.params), combo, strict=True))}, positive)
                    for combo in itertools.product(*pools))

    return value


def _atom(lit: adl.Lit) -> Atom:
    pred, args, v = lit
    return Atom(pred, tuple(Var(a[1:]) if a.startswith("?") else a for a in args), v)
