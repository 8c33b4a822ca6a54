"""Heuristics for regression search.

HSPr's idea: one forward relaxed exploration from the current belief gives
an additive cost estimate ``h_add`` for every atom; a regression node's
estimate is the sum over its atoms, computed with no further search.  Atoms
the relaxation cannot reach make a subgoal a dead end.  The exploration
needs the belief to list its true facts and the operators to be groundable
without generators; otherwise the planner falls back to counting unmet atoms.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.grounding import Grounder


def can_relax(grounder: Grounder, belief: Any) -> bool:
    dom = grounder.domain
    return (
        hasattr(belief, "atoms")
        and hasattr(belief, "facts")
        and not any(op.generators for op in dom.operators)
        and all(p.test is None and p.boolean for p in dom.predicates.values())
    )


def hadd_table(
    grounder: Grounder, levels: LevelMap, drop: frozenset[str], cost: Callable[[Action], float]
) -> dict[Atom, float]:
    """Additive relaxed cost of each reachable atom (true ones cost 0)."""
    dom = grounder.domain
    table: dict[Atom, float] = {a: 0.0 for a in grounder.belief.atoms()}
    acts: list[tuple[Action, list[Atom], float, tuple[Atom, ...]]] = []
    for op in dom.operators:
        for b in grounder._fill(op, {}):
            act = op.instantiate(b)
            pre = [p for p in act.preconditions(levels.level(act)) if p.predicate not in drop]
            acts.append((act, pre, cost(act), act.effects()))
    true_now = set(table)

    def pcost(p: Atom) -> float:
        if p.value is False:
            if Atom(p.predicate, p.args, True) not in true_now:
                return 0.0
        return table.get(p, math.inf)

    for _ in range(len(acts) + 1):  # a fixpoint is reached in at most |acts| sweeps
        changed = False
        for _act, pre, c, effs in acts:
            total = c
            for p in pre:
                total += pcost(p)
                if total == math.inf:
                    break
            if total == math.inf:
                continue
            for e in effs:
                if total < table.get(e, math.inf):
                    table[e] = total
                    changed = True
        if not changed:
            break
    return table


class HAdd:
    """``h(G) = Σ h_add(a)``; ``inf`` for an unreachable atom."""

    def __init__(self, table: dict[Atom, float], holds: Callable[[Atom], bool]) -> None:
        self.table = table
        self.holds = holds

    def __call__(self, g: Goal) -> float:
        total = 0.0
        for a in g.atoms:
            if self.holds(a):
                continue
            total += self.table.get(a, math.inf)
            if total == math.inf:
                return total
        return total
