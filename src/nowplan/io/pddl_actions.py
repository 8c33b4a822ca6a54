"""PDDL actions compiled to operators of the core model (see :mod:`nowplan.io.pddl_adl`).

:func:`compile_action` turns one parsed action into operators: its
precondition and effects are compiled (quantifiers over the problem's
objects, static facts evaluated, conditional effects split, DNF), and an
``(either ...)`` parameter gives one operator per type.  When the lifted
compilation passes a bound (too many effect conditions, typically one per
object of a ``forall``), the action is compiled once per binding of its
parameters instead (at most :data:`MAX_BINDINGS`), where static facts often
decide most conditions (miconic-ADL's ``stop ?f``: only the passengers whose
origin or destination is ``?f`` keep a condition); each such operator pins
its parameters with static equalities ``(= ?f f3)``.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Mapping
from dataclasses import dataclass

from nowplan.core.atoms import Atom, Term, Var
from nowplan.core.operators import Operator, Precondition
from nowplan.errors import CompilationBoundError, PDDLError, UnsupportedPDDLError
from nowplan.io import pddl_adl as adl
from nowplan.io.pddl_ast import TRUE
from nowplan.io.pddl_check import EQUALITY, Checker
from nowplan.io.pddl_cost import FunctionCost, constant_cost
from nowplan.io.pddl_syntax import ActionDef, DomainDef

MAX_TYPE_VARIANTS = 64  # operators from the (either ...) parameters of one action
MAX_BINDINGS = 5_000  # bindings of an action's parameters compiled one by one


@dataclass(frozen=True)
class World:
    """What the compilation knows of the problem: objects, static facts, function values."""

    objects: Mapping[str, str | None]
    init: frozenset[tuple[str, tuple[str, ...]]]
    values: Mapping[tuple[str, tuple[str, ...]], float]
    path: str = ""  # the problem file (function values come from its :init)


class NeedsObjects(Exception):
    pass


def objects_of(checker: Checker, world: World | None) -> Callable[[tuple[str, ...]], list[str]]:
    """The objects (and constants) fitting some types; raises NeedsObjects without a problem."""
    memo: dict[tuple[str, ...], list[str]] = {}

    def objects_of(types: tuple[str, ...]) -> list[str]:
        if world is None:
            raise NeedsObjects()
        hit = memo.get(types)
        if hit is None:
            hit = memo[types] = sorted(o for o, t in world.objects.items() if checker.is_a(t, types))
        return hit

    return objects_of


def static_value(static: frozenset[str], world: World | None) -> Callable[[adl.Lit], bool | None]:
    """A ground literal's value when it is an equality or a static fact of the problem (else None)."""
    def value(lit: adl.Lit) -> bool | None:
        pred, args, v = lit
        if any(a.startswith("?") for a in args):
            return None
        if pred == EQUALITY:
            return (args[0] == args[1]) == v
        if world is None or pred not in static:
            return None
        return ((pred, args) in world.init) == v

    return value


LIFTED_ENOUGH = 16  # lifted variants of one action kept without trying the per-binding compilation


def atom_of(lit: adl.Lit) -> Atom:
    pred, args, v = lit
    terms: tuple[Term, ...] = tuple(Var(a[1:]) if a.startswith("?") else a for a in args)
    return Atom(pred, terms, v)


def compile_action(act: ActionDef, d: DomainDef, checker: Checker, static: frozenset[str],
                   world: World | None, derived: adl.Derived,
                   oracle: Callable[[adl.Lit], bool | None] | None = None) -> tuple[list[Operator], bool]:
    """The operators of one action, and whether it increases total-cost.

    ``oracle`` (default: :func:`static_value`) gives the ground literals known in every state.
    """
    where = f"action {act.name}"
    objs = objects_of(checker, world)
    value = oracle if oracle is not None else static_value(static, world)
    try:
        pre = adl.to_nnf(act.precondition or TRUE, {}, objs, value, derived=derived)
        flat = adl.flatten_effects(act.effect, objs, value, where, derived)
    except NeedsObjects:
        raise UnsupportedPDDLError(f"{where} quantifies over objects; quantifiers are compiled over a problem's "
                                   "objects: read the domain together with a problem (load_pddl)",
                                   path=d.path, line=act.line) from None
    except adl.TooLarge as exc:
        raise CompilationBoundError(f"{exc}; it is not compiled", path=d.path, line=act.line) from None
    pinned = False
    try:
        variants = adl.compile_action(pre, flat, where)
    except adl.TooLarge as exc:
        if world is None or not act.params:
            raise CompilationBoundError(f"{exc}; it is not compiled", path=d.path, line=act.line) from None
        variants = _per_binding(act, d, objs, value, derived, str(exc))
        pinned = True
    if not pinned and world is not None and act.params and flat.conditional and len(variants) > LIFTED_ENOUGH:
        # Many lifted variants (IPC airport-ADL: 2**k over its forall-when effects) are mostly
        # contradicted by static facts once the parameters are bound: per binding is often far smaller.
        try:
            per = _per_binding(act, d, objs, value, derived, f"{where} has {len(variants)} lifted variants")
        except UnsupportedPDDLError:
            per = None
        if per is not None and len(per) < len(variants):
            variants, pinned = per, True
    type_choices: list[list[str | None]] = []
    for p in act.params:
        if pinned:  # the equalities pin the values; an (either ...) type needs no split
            type_choices.append([p.types[0] if len(p.types) == 1 else None])
            continue
        alts: list[str | None] = [t for t in p.types if not any(o != t and o in checker.ancestors(t) for o in p.types)]
        type_choices.append(alts or [None])
    combos = list(itertools.islice(itertools.product(*type_choices), MAX_TYPE_VARIANTS + 1))
    if len(combos) > MAX_TYPE_VARIANTS:
        raise UnsupportedPDDLError(f"{where} has (either ...) parameters with more than {MAX_TYPE_VARIANTS} "
                                   "combinations of types", path=d.path, line=act.line)
    params = tuple(Var(p.name[1:]) for p in act.params)
    if flat.costs:
        exprs = flat.costs
        const = constant_cost(exprs)
        if const is not None and const < 0:
            raise PDDLError(f"{where}: action costs must be >= 0, got {const:g}", path=d.path, line=act.line)
        cost: float | FunctionCost | None = const if const is not None else FunctionCost(
            act.name, tuple(p.name for p in act.params), exprs,
            world.values if world is not None else None, world.path if world is not None else d.path)
    else:
        cost = None
    order = adl.literal_order([pre, *(c for c, _ in flat.conditional)])
    ops = []
    n = len(variants) * len(combos)
    for k, (var, types) in enumerate(itertools.product(variants, combos)):
        dels = [atom_of(lit) for lit in var.effects if not lit[2]]
        adds = [atom_of(lit) for lit in var.effects if lit[2]]
        ops.append(Operator(
            act.name if n == 1 else f"{act.name}-v{k + 1}",
            params,
            tuple(Precondition(atom_of(lit), 1) for lit in sorted(var.pre, key=lambda x: (_rank(x, order), x))),
            tuple(dels + adds),
            cost=cost if cost is not None else 1.0,
            param_types=tuple(types),
            pddl_name=None if n == 1 else act.name,
        ))
    return ops, cost is not None




def _rank(lit: adl.Lit, order: Mapping[adl.Lit, int]) -> int:
    """Pinning equalities first (the grounder binds the parameters with them), then the file's order."""
    if lit[0] == EQUALITY and lit[2] and lit[1][0].startswith("?") and not lit[1][1].startswith("?"):
        return -1
    return order.get(lit, 1 << 30)


def _per_binding(act: ActionDef, d: DomainDef, objs: Callable[[tuple[str, ...]], list[str]],
                 value: Callable[[adl.Lit], bool | None], derived: adl.Derived, why: str) -> list[adl.Variant]:
    """The action compiled once per binding of its parameters, each variant pinned by ``(= ?p o)``."""
    where = f"action {act.name}"
    pools = [objs(p.types) for p in act.params]
    n = 1
    for pool in pools:
        n *= len(pool)
    if n > MAX_BINDINGS:
        raise CompilationBoundError(f"{why}; compiled per binding of its parameters it would need {n} bindings "
                                   f"(bound {MAX_BINDINGS}); it is not compiled", path=d.path, line=act.line)
    out: list[adl.Variant] = []
    for combo in itertools.product(*pools):
        sub = {p.name: o for p, o in zip(act.params, combo, strict=True)}
        shown = " ".join(combo)
        try:
            pre = adl.to_nnf(act.precondition or TRUE, sub, objs, value, derived=derived)
            if pre is False:
                continue
            flat = adl.flatten_effects(act.effect, objs, value, where, derived, sub)
            variants = adl.compile_action(pre, flat, f"{where} ({act.name} {shown})")
        except adl.TooLarge as exc:
            raise CompilationBoundError(f"{exc}, even compiled per binding of its parameters; it is not compiled",
                                       path=d.path, line=act.line) from None
        pins = frozenset((EQUALITY, (v, o), True) for v, o in sub.items())
        out.extend(adl.Variant(v.pre | pins, v.effects) for v in variants)
        if len(out) > adl.MAX_OPERATORS * 16:
            raise CompilationBoundError(f"{why}; compiled per binding of its parameters it needs more than "
                                       f"{adl.MAX_OPERATORS * 16} operators; it is not compiled",
                                       path=d.path, line=act.line)
    return out
