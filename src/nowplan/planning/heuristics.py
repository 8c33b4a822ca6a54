"""Heuristics for regression search.

HSPr's idea: one forward relaxed exploration from the current belief gives
an additive cost estimate ``h_add`` for every atom; a regression node's
estimate is the sum over its atoms, computed with no further search.  Atoms
the relaxation cannot reach make a subgoal a dead end.  The exploration is
Knuth's generalisation of Dijkstra's algorithm (exact for ``h_add``, whose
action costs are monotone in their preconditions' costs).

The ground actions are cached per (domain, objects, static facts), since
the planner is called many times on the same problem by the executive.  The
exploration needs the belief to list its true facts and the operators to be
groundable without generators; otherwise the planner counts unmet atoms.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable
from dataclasses import dataclass
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


@dataclass(frozen=True)
class GroundAction:
    action: Action
    pre: tuple[tuple[Atom, int], ...]  # (atom, criticality), statics left out
    effects: tuple[Atom, ...]


_CACHE: dict[Any, tuple[GroundAction, ...]] = {}
_CACHE_SIZE = 16


def ground_all(grounder: Grounder, drop: frozenset[str]) -> tuple[GroundAction, ...]:
    """Every ground action of the problem (static preconditions checked), cached."""
    dom = grounder.domain
    statics = tuple(sorted((p, tuple(sorted(map(repr, grounder.belief.facts(p))))) for p in drop))
    key = (dom, tuple(sorted(grounder.objects.items(), key=repr)), statics)
    hit = _CACHE.get(key)
    if hit is not None:
        return hit
    out: list[GroundAction] = []
    for op in dom.operators:
        for b in grounder._fill(op, {}):
            act = op.instantiate(b)
            pre = tuple(
                (p.atom.bind(b), p.criticality) for p in op.preconditions if p.atom.predicate not in drop
            )
            out.append(GroundAction(act, pre, act.effects()))
    if len(_CACHE) >= _CACHE_SIZE:
        _CACHE.pop(next(iter(_CACHE)))
    _CACHE[key] = tuple(out)
    return _CACHE[key]


def hadd_table(
    grounder: Grounder, levels: LevelMap, drop: frozenset[str], cost: Callable[[Action], float]
) -> dict[Atom, float]:
    """Additive relaxed cost of each reachable atom (true ones cost 0)."""
    acts = ground_all(grounder, drop)
    true_now = set(grounder.belief.atoms())
    table: dict[Atom, float] = {a: 0.0 for a in true_now}
    waiting: dict[Atom, list[int]] = {}  # atom -> actions that need it
    missing = [0] * len(acts)
    total = [0.0] * len(acts)
    queue: list[tuple[float, int, Atom]] = []
    tick = 0
    for k, ga in enumerate(acts):
        total[k] = cost(ga.action)
        level = levels.level(ga.action)
        for atom, crit in ga.pre:
            if crit <= level:
                continue  # hidden at this abstraction level
            if atom.value is False and Atom(atom.predicate, atom.args, True) not in true_now:
                continue  # already false
            missing[k] += 1
            waiting.setdefault(atom, []).append(k)
    for a in true_now:
        queue.append((0.0, tick, a))
        tick += 1
    for k, ga in enumerate(acts):
        if missing[k] == 0:
            for e in ga.effects:
                if total[k] < table.get(e, math.inf):
                    table[e] = total[k]
                    queue.append((total[k], tick, e))
                    tick += 1
    heapq.heapify(queue)
    done: set[Atom] = set()
    while queue:
        c, _, a = heapq.heappop(queue)
        if a in done or c > table.get(a, math.inf):
            continue
        done.add(a)
        for k in waiting.get(a, ()):
            missing[k] -= 1
            total[k] += c
            if missing[k] == 0:
                for e in acts[k].effects:
                    if total[k] < table.get(e, math.inf):
                        table[e] = total[k]
                        heapq.heappush(queue, (total[k], tick, e))
                        tick += 1
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

