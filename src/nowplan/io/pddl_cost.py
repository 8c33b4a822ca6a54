"""Action costs read from PDDL: constants, or expressions over static numeric functions.

``(increase (total-cost) (road-length ?l1 ?l2))`` gives the operator a
:class:`FunctionCost`: a callable ``cost(bindings, belief)`` (the core
model's ``CostFn``) that evaluates the expression for a ground action with
the values the problem's ``:init`` gives (``(= (road-length a b) 5)``).  A
ground action whose function has no value, or whose cost is negative, is a
:class:`nowplan.errors.PDDLError` naming the function, the action and the file.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Var
from nowplan.core.operators import StateFreeCost
from nowplan.errors import PDDLError
from nowplan.io.pddl_adl import evaluate
from nowplan.io.pddl_ast import NConst, NExpr, NFunc, NOp


def constant_cost(exprs: tuple[NExpr, ...]) -> float | None:
    """The sum of ``exprs`` when no function appears in them (else None)."""
    def const(x: NExpr) -> bool:
        return isinstance(x, NConst) or (isinstance(x, NOp) and all(const(a) for a in x.args))

    if not all(const(x) for x in exprs):
        return None
    return sum(evaluate(x, _no_values) for x in exprs)


def _no_values(name: str, args: tuple[str, ...], line: int) -> float:  # pragma: no cover - never called
    raise AssertionError(name)


def functions_of(x: NExpr) -> set[tuple[str, int]]:
    if isinstance(x, NFunc):
        return {(x.name, len(x.args))}
    if isinstance(x, NOp):
        return {f for a in x.args for f in functions_of(a)}
    return set()


def show_expr(x: NExpr) -> str:
    if isinstance(x, NConst):
        v = x.value
        return str(int(v)) if float(v).is_integer() else repr(v)
    if isinstance(x, NFunc):
        return "(" + " ".join((x.name, *x.args)) + ")"
    return "(" + " ".join((x.op, *(show_expr(a) for a in x.args))) + ")"


@dataclass(frozen=True)
class FunctionCost(StateFreeCost):
    """The cost of a ground action: its ``(increase (total-cost) ...)`` expressions evaluated."""

    action: str
    params: tuple[str, ...]  # "?x", in the operator's parameter order
    exprs: tuple[NExpr, ...]
    values: Mapping[tuple[str, tuple[str, ...]], float] | None = field(compare=False, hash=False)
    path: str = ""

    def __call__(self, bindings: Mapping[Var, Any], belief: Any = None) -> float:
        sub = {f"?{v.name}": str(o) for v, o in bindings.items()}

        def value(name: str, args: tuple[str, ...], line: int) -> float:
            ground = tuple(sub.get(a, a) for a in args)
            if self.values is None:
                raise PDDLError(f"the cost of action {self.action} needs the value of ({name} ...) from a problem's "
                                ":init; read the domain with a problem (load_pddl)", path=self.path, line=line)
            v = self.values.get((name, ground))
            if v is None:
                fact = "(" + " ".join((name, *ground)) + ")"
                raise PDDLError(f"the :init gives no value for {fact}, needed for the cost of "
                                f"action {self.action}; add (= {fact} N)", path=self.path)
            return v

        try:
            c = sum(evaluate(x, value) for x in self.exprs)
        except ZeroDivisionError:
            raise PDDLError(f"the cost of action {self.action} divides by zero for "
                            f"{' '.join(sub.get(p, p) for p in self.params)}", path=self.path) from None
        if c < 0:
            raise PDDLError(f"action {self.action} costs {c:g} < 0 for {' '.join(sub.get(p, p) for p in self.params)}; "
                            "action costs must be >= 0", path=self.path)
        return c
