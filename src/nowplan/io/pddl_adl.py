"""ADL compiled to STRIPS by grounding quantifiers over the finite objects.

* ``forall`` / ``exists`` (in preconditions, goals, effect conditions) become
  conjunctions / disjunctions over the objects of the variable's type(s)
  (at most :data:`MAX_QUANTIFIED` instances per quantifier);
* negation is pushed to the atoms (negation normal form); ground atoms of
  static predicates and ground equalities are replaced by their value in the
  initial state, which removes most of what quantifiers add;
* a condition becomes a disjunctive normal form: one operator per disjunct
  (at most :data:`MAX_DISJUNCTS` disjuncts per operator);
* conditional effects (``when``, also inside ``forall`` effects) are
  compiled away by splitting the action over the combinations of its effect
  conditions: for the subset S of conditions that hold, the variant requires
  every condition in S and the negation of every other one, and has the
  effects of S.  With k distinct conditions this is 2**k variants, so k is
  bounded (:data:`MAX_CONDITIONS`) and so is the total number of operators
  per action (:data:`MAX_OPERATORS`).  A variant without effects (no
  condition holds and there is no unconditional effect) is left out: a plan
  never needs an action that changes nothing.

Derived predicates (axioms) that are not recursive are compiled by
replacing each of their atoms by the disjunction of their definitions (and a
negated atom by the negation of it: closed-world semantics, exact for
non-recursive axioms).

Every bound that is hit raises :class:`nowplan.errors.UnsupportedPDDLError`
naming the action (or the goal), the construct and the bound.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Union

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
    NConst,
    NExpr,
    NFunc,
    NOp,
    TypedName,
)

MAX_QUANTIFIED = 10_000  # instances of one quantifier's variables
MAX_DISJUNCTS = 256  # disjuncts of one condition in DNF
# nodes of one condition in negation normal form while derived predicates' definitions are substituted into
# it: past this the DNF bound is out of reach in practice, and reading fails over to evaluating them by rules
MAX_SUBSTITUTED_NODES = 200_000
MAX_CONDITIONS = 10  # distinct effect conditions of one action (2**10 variants)
MAX_OPERATORS = 1024  # operators compiled from one action

Lit = tuple[str, tuple[str, ...], bool]  # predicate, args ("?x" or objects), value
# negation normal form: True, False, a literal, or ("and" | "or", children)
NNF = Union[bool, "LitNode", "Junction"]


@dataclass(frozen=True)
class LitNode:
    lit: Lit
    line: int = field(default=0, compare=False, hash=False)


@dataclass(frozen=True)
class Junction:
    op: str  # "and" | "or"
    parts: tuple[NNF, ...]


class TooLarge(Exception):
    """A bound of the compilation is exceeded; the message names it."""


ObjectsOf = Callable[[tuple[str, ...]], Sequence[str]]
StaticValue = Callable[[Lit], "bool | None"]


def _sub(args: tuple[str, ...], sub: dict[str, str]) -> tuple[str, ...]:
    return tuple(sub.get(a, a) for a in args)


def _instances(params: tuple[TypedName, ...], objects_of: ObjectsOf, what: str) -> list[dict[str, str]]:
    pools = [objects_of(p.types) for p in params]
    n = 1
    for pool in pools:
        n *= len(pool)
    if n > MAX_QUANTIFIED:
        raise TooLarge(f"{what} has {n} instances over the objects (bound {MAX_QUANTIFIED})")
    return [dict(zip((p.name for p in params), combo, strict=True)) for combo in itertools.product(*pools)]


def _junction(op: str, parts: list[NNF]) -> NNF:
    """``and``/``or`` with constants folded and nested junctions of the same kind flattened."""
    unit, zero = (True, False) if op == "and" else (False, True)
    flat: list[NNF] = []
    for p in parts:
        if p is zero:
            return zero
        if p is unit:
            continue
        if isinstance(p, Junction) and p.op == op:
            flat.extend(p.parts)
        else:
            flat.append(p)
    if not flat:
        return unit
    return flat[0] if len(flat) == 1 else Junction(op, tuple(flat))


# derived predicates: name -> its definitions (parameters, condition); an atom is true when one holds
Derived = Mapping[str, Sequence[tuple[tuple[str, ...], Formula]]]


def to_nnf(
    f: Formula, sub: dict[str, str], objects_of: ObjectsOf, static: StaticValue, neg: bool = False,
    derived: Derived | None = None, budget: list[int] | None = None,
) -> NNF:
    """``f`` (negated when ``neg``) in negation normal form, quantifiers expanded, statics evaluated.

    Atoms of (non-recursive) derived predicates are replaced by their definitions; then the condition may
    have at most :data:`MAX_SUBSTITUTED_NODES` nodes (``budget``: what is left of them, shared by the
    recursive calls), else :class:`TooLarge` is raised as soon as that is known, not after the expansion
    (IPC-2004 optical telegraph: four ``blocked`` goals, each a ``forall`` over the transitions of three
    rules of ``exists``, expanded to millions of nodes before the DNF bound refused them).
    """
    if derived:
        if budget is None:
            budget = [MAX_SUBSTITUTED_NODES]
        budget[0] -= 1
        if budget[0] < 0:
            raise TooLarge(f"substituting the derived predicates' definitions gives more than "
                           f"{MAX_SUBSTITUTED_NODES} nodes in negation normal form")
    if isinstance(f, FAtom) and derived and f.pred in derived:
        args = _sub(f.args, sub)
        bodies = [to_nnf(body, dict(zip(params, args, strict=True)), objects_of, static, neg, derived, budget)
                  for params, body in derived[f.pred]]
        return _junction("and" if neg else "or", bodies)
    if isinstance(f, FAtom):
        lit: Lit = (f.pred, _sub(f.args, sub), not neg)
        known = static(lit)
        if known is not None:
            return known
        return LitNode(lit, f.line)
    if isinstance(f, FNot):
        return to_nnf(f.arg, sub, objects_of, static, not neg, derived, budget)
    if isinstance(f, FAnd | FOr):
        op = "and" if isinstance(f, FAnd) else "or"
        if neg:
            op = "or" if op == "and" else "and"
        return _junction(op, [to_nnf(p, sub, objects_of, static, neg, derived, budget) for p in f.parts])
    assert isinstance(f, FQuant)
    op = "and" if (f.kind == "forall") != neg else "or"
    parts = []
    for inst in _instances(f.params, objects_of, f"the ({f.kind} ...) on line {f.line}"):
        parts.append(to_nnf(f.body, {**sub, **inst}, objects_of, static, neg, derived, budget))
        if parts[-1] is (op == "or"):  # a true disjunct / false conjunct decides it
            break
    return _junction(op, parts)


def literal_order(xs: Sequence[NNF]) -> dict[Lit, int]:
    """Each literal's first position in ``xs`` (both signs), to keep the file's order of conditions."""
    out: dict[Lit, int] = {}

    def walk(x: NNF) -> None:
        if isinstance(x, LitNode):
            p, a, v = x.lit
            for lit in ((p, a, v), (p, a, not v)):
                out.setdefault(lit, len(out))
        elif isinstance(x, Junction):
            for y in x.parts:
                walk(y)

    for x in xs:
        walk(x)
    return out


def negate(x: NNF) -> NNF:
    if isinstance(x, bool):
        return not x
    if isinstance(x, LitNode):
        p, a, v = x.lit
        return LitNode((p, a, not v), x.line)
    return Junction("or" if x.op == "and" else "and", tuple(negate(p) for p in x.parts))


def _consistent(lits: frozenset[Lit]) -> bool:
    for p, a, v in lits:
        if v and (p, a, False) in lits:
            return False
        if p == "=" and not v and len(a) == 2 and a[0] == a[1]:
            return False
    return True


def dnf(x: NNF, what: str) -> list[frozenset[Lit]]:
    """The consistent, non-subsumed disjuncts of ``x`` (``[]``: false; ``[frozenset()]``: true)."""
    if x is True:
        return [frozenset()]
    if x is False:
        return []
    if isinstance(x, LitNode):
        return [frozenset({x.lit})]
    assert isinstance(x, Junction)
    if x.op == "or":
        out: list[frozenset[Lit]] = []
        for p in x.parts:
            out.extend(dnf(p, what))
            if len(out) > MAX_DISJUNCTS * 4:
                raise TooLarge(f"{what} has more than {MAX_DISJUNCTS} disjuncts in disjunctive normal form")
        return _minimal(out, what)
    acc: list[frozenset[Lit]] = [frozenset()]
    for p in x.parts:
        nxt = [a | b for a in acc for b in dnf(p, what)]
        acc = _minimal([c for c in nxt if _consistent(c)], what)
        if not acc:
            return []
    return acc


def _minimal(ds: list[frozenset[Lit]], what: str) -> list[frozenset[Lit]]:
    uniq = sorted(set(ds), key=lambda d: (len(d), sorted(d)))
    out: list[frozenset[Lit]] = []
    for d in uniq:
        if not any(o <= d for o in out):
            out.append(d)
    if len(out) > MAX_DISJUNCTS:
        raise TooLarge(f"{what} has {len(out)} disjuncts in disjunctive normal form (bound {MAX_DISJUNCTS})")
    return out


# --------------------------------------------------------------------------- effects


@dataclass(frozen=True)
class FlatEffects:
    """Unconditional literals, conditional groups (condition, literals) and the cost expressions."""

    base: tuple[Lit, ...]
    conditional: tuple[tuple[NNF, tuple[Lit, ...]], ...]
    costs: tuple[NExpr, ...]


def flatten_effects(e: Effect | None, objects_of: ObjectsOf, static: StaticValue, where: str,
                    derived: Derived | None = None, sub: dict[str, str] | None = None) -> FlatEffects:
    base: list[Lit] = []
    groups: dict[NNF, list[Lit]] = {}
    costs: list[NExpr] = []

    def walk(x: Effect, sub: dict[str, str], cond: NNF) -> None:
        if isinstance(x, ELit):
            lit: Lit = (x.atom.pred, _sub(x.atom.args, sub), x.value)
            if cond is True:
                base.append(lit)
            elif cond is not False:
                groups.setdefault(cond, []).append(lit)
        elif isinstance(x, EAnd):
            for p in x.parts:
                walk(p, sub, cond)
        elif isinstance(x, EWhen):
            c = to_nnf(x.cond, sub, objects_of, static, derived=derived)
            walk(x.effect, sub, _junction("and", [cond, c]))
        elif isinstance(x, EForall):
            for inst in _instances(x.params, objects_of, f"the (forall ...) effect on line {x.line}"):
                walk(x.effect, {**sub, **inst}, cond)
        else:
            assert isinstance(x, ECost)
            if cond is not True:
                raise TooLarge(f"{where} increases total-cost inside a conditional effect (line {x.line}); "
                               "only unconditional action costs are supported")
            costs.append(_sub_expr(x.amount, sub))

    if e is not None:
        walk(e, dict(sub or {}), True)
    _unconditional_when_trivial(base, groups)
    return FlatEffects(tuple(base), tuple((c, tuple(ls)) for c, ls in groups.items()), tuple(costs))


def _unconditional_when_trivial(base: list[Lit], groups: dict[NNF, list[Lit]]) -> None:
    """Make unconditional the conditional effects whose condition does not matter.

    ``(when p (not p))`` is the delete ``(not p)``: deleting a false atom changes
    nothing, and an add of ``p`` by the same action still wins (deletes apply
    first).  ``(when (not p) p)`` is the add ``p`` provided the action deletes
    no atom of ``p``'s predicate (else the add would now win over that delete).
    IPC domains use these idioms in every ``forall`` that clears an old value
    (schedule's ``do-roll`` has 11 such conditions: 2**11 variants otherwise).
    """
    deleted = {lit[0] for lit in base if not lit[2]}
    deleted |= {lit[0] for lits in groups.values() for lit in lits if not lit[2]}
    for cond in list(groups):
        if not isinstance(cond, LitNode):
            continue
        pred, args, value = cond.lit
        lits = groups[cond]
        flipped = (pred, args, not value)
        if flipped in lits and (value or pred not in deleted):
            lits.remove(flipped)
            base.append(flipped)
            if not lits:
                del groups[cond]


def _sub_expr(x: NExpr, sub: dict[str, str]) -> NExpr:
    if isinstance(x, NFunc):
        return NFunc(x.name, _sub(x.args, sub), x.line)
    if isinstance(x, NOp):
        return NOp(x.op, tuple(_sub_expr(a, sub) for a in x.args))
    return x


@dataclass(frozen=True)
class Variant:
    """One compiled operator: its precondition literals and its effect literals."""

    pre: frozenset[Lit]
    effects: tuple[Lit, ...]


def compile_action(pre: NNF, eff: FlatEffects, where: str) -> list[Variant]:
    """The STRIPS variants of an action whose precondition is ``pre`` (NNF) and effects ``eff``."""
    k = len(eff.conditional)
    if k > MAX_CONDITIONS:
        raise TooLarge(f"{where} has {k} distinct effect conditions, which would need 2**{k} operators "
                       f"(bound {MAX_CONDITIONS} conditions)")
    out: list[Variant] = []
    for mask in range(1 << k):
        parts = [pre]
        effects = list(eff.base)
        for i, (cond, lits) in enumerate(eff.conditional):
            if mask >> i & 1:
                parts.append(cond)
                effects.extend(lits)
            else:
                parts.append(negate(cond))
        if k and not effects:
            continue  # a variant that changes nothing is never needed in a plan
        for d in dnf(_junction("and", parts), f"the precondition of {where}"):
            out.append(Variant(d, tuple(dict.fromkeys(effects))))
            if len(out) > MAX_OPERATORS:
                raise TooLarge(f"{where} compiles to more than {MAX_OPERATORS} operators "
                               f"({k} effect conditions and disjunctive preconditions)")
    return out


def evaluate(x: NExpr, values: Callable[[str, tuple[str, ...], int], float]) -> float:
    """A numeric expression whose functions are looked up by ``values(name, args, line)``."""
    if isinstance(x, NConst):
        return x.value
    if isinstance(x, NFunc):
        return values(x.name, x.args, x.line)
    vals = [evaluate(a, values) for a in x.args]
    if x.op == "+":
        return sum(vals)
    if x.op == "-":
        return -vals[0] if len(vals) == 1 else vals[0] - sum(vals[1:])
    if x.op == "*":
        out = 1.0
        for v in vals:
            out *= v
        return out
    out = vals[0]
    for v in vals[1:]:
        if v == 0:
            raise ZeroDivisionError("division by zero in an action cost")
        out /= v
    return out
