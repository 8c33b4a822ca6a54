"""Operator parameters the planner can never bind to a value the belief holds (checked once per run).

The planner binds an operator's parameters from the goal (through the effects that make a fact
true), from its
generators, by joining its static preconditions with the listed facts, and otherwise from the
problem's objects of the parameter's type.  (A domain without generators, tested or valued
predicates is ground once from the facts that can become true, which binds such parameters; one
with them is ground call by call, as said here.)  A parameter that only a precondition on a changing
fluent mentions therefore ranges over objects only: when the belief lists such a fluent with a
value there that is no object (a pose "0.0,2.0", a number), no instance of the operator uses it,
and planning fails with "search space exhausted" and no word why.  A held-out greenhouse's
``take(r, t, q)``, whose ``lies(t, q)`` held a pose, did so (benchmarks/results/heldout12).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from nowplan.belief.protocols import ListsFacts
from nowplan.core.atoms import Var
from nowplan.core.domain import Domain


def unbindable_parameters(domain: Domain, objects: Mapping[str, Any], belief: Any) -> str | None:
    """One line naming the first such operator parameter, the fact and the fixes; ``None``: there is none."""
    if not isinstance(belief, ListsFacts):
        return None
    if not any(op.generators for op in domain.operators) and all(
            p.test is None and p.boolean for p in domain.predicates.values()):
        return None  # ground from the reachable facts, which binds them
    statics = domain.static_predicates
    for op in domain.operators:
        bound = {v for g in op.generators for v in g.outputs}
        bound |= {a for p in op.preconditions if p.static or p.atom.predicate in statics
                  for a in p.atom.args if isinstance(a, Var)}
        # an effect that makes a fact true is unified with the goal's atoms, which binds its arguments
        # to any value (put(t, q) with free(q) and lies(t, q) binds q from a goal lies(sprayer, "0,2"))
        bound |= {a for e in op.effects if e.value is not False for a in e.args if isinstance(a, Var)}
        for pre in op.preconditions:
            a = pre.atom
            if pre.static or a.predicate in statics:
                continue
            for k, arg in enumerate(a.args):
                if not isinstance(arg, Var) or arg in bound or arg not in op.params:
                    continue
                for args in belief.facts(a.predicate):
                    if len(args) != len(a.args) or args[k] in objects:
                        continue
                    fact = f"{a.predicate}({', '.join(str(x) for x in args)})"
                    return (f"operator {op.name}: parameter {arg} is bound from the problem's objects only "
                            f"(no generator or static precondition binds it), but the belief holds {fact}, "
                            f"whose '{args[k]}' is no object, so no instance of {op.name} can use it; give "
                            f"{op.name} a Generator for {arg}, or declare the value in Problem(objects=...)")
    return None
