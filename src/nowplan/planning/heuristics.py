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
The regression search asks for its values through
:mod:`nowplan.planning.hadd_relevant`, which explores only the facts a call
needs and keeps them across calls; :func:`hadd_ids` is the reference it is
tested against.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable
from typing import Any

from nowplan.core.atoms import Atom
from nowplan.belief.protocols import ListsFacts, offers
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action, reads_nothing
from nowplan.planning.ground_task import GroundAction, GroundTask, instances
from nowplan.planning.grounding import Grounder


def relax_unsupported(grounder: Grounder, belief: Any) -> str | None:
    """Why the ground relaxed exploration (h_add, h_max, h_FF) cannot run here, or ``None`` if it can."""
    dom = grounder.domain
    if not (grounder.lists_facts if grounder.belief is belief else offers(belief, ListsFacts)):
        return f"the belief {type(belief).__name__} does not list its facts (no facts()/atoms())"
    hit = dom.facts.derived.get("relax unsupported")
    if hit is not None and hit[0] is dom.operators and hit[1] is dom.predicates:
        return hit[2]  # type: ignore[no-any-return]
    why: str | None = None
    for op in dom.operators:
        if op.generators:
            why = f"operator {op.name} has generators"
            break
    if why is None:
        for p in dom.predicates.values():
            if p.test is not None:
                why = f"predicate {p.name} has a test"
                break
            if not p.boolean:
                why = f"predicate {p.name} is not boolean"
                break
    dom.facts.derived["relax unsupported"] = (dom.operators, dom.predicates, why)
    return why


def lazy_by_default(domain: Any) -> bool:
    """Whether the lazy relaxation estimates in place of the ground one by default: tested
    predicates are all that keeps the ground relaxation from the domain (no generators, every
    predicate boolean), or every generator declares that its values do not read the goal
    (``Generator(reads=reads_nothing)``: its achievers are the same in every subgoal, so the lazy
    exploration over them is as sound as over tested predicates).  Otherwise the planner counts
    unmet atoms (a held-out greenhouse, benchmarks/results/heldout12: 10,392 expansions and
    15 CPU s for hpn's runs of 3 plants by counting, 3.5 CPU s relaxed)."""
    gens = [g for op in domain.operators for g in op.generators]
    if gens:
        return all(g.reads is reads_nothing for g in gens)
    return (all(p.boolean for p in domain.predicates.values())
            and any(p.test is not None for p in domain.predicates.values()))


def can_relax(grounder: Grounder, belief: Any) -> bool:
    return relax_unsupported(grounder, belief) is None


_CACHE: dict[Any, tuple[GroundAction, ...]] = {}
_CACHE_SIZE = 16


def ground_all(grounder: Grounder, drop: frozenset[str]) -> tuple[GroundAction, ...]:
    """Every ground action of the problem (static preconditions checked), instantiated and bound one by one.

    The reference that :class:`GroundTask`'s bulk build is tested against (cached).
    """
    dom = grounder.domain
    statics = tuple(sorted((p, tuple(sorted(map(repr, grounder.belief.facts(p))))) for p in drop))
    # operators compare without their costs: two domains equal but for costs must not share actions
    costs = tuple(id(o.cost) if callable(o.cost) else o.cost for o in dom.operators)
    key = (dom, costs, tuple(sorted(grounder.objects.items(), key=repr)), statics)
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


def ground_task(grounder: Grounder, drop: frozenset[str]) -> GroundTask:
    """The problem's ground actions as fact ids, kept with the problem's shared grounding answers."""
    dom = grounder.domain
    store = dom.facts.grounding
    key = ("task", grounder.signature, drop)
    hit = store.get(key)
    if not isinstance(hit, GroundTask):
        fills = [(i, instances(grounder, op)) for i, op in enumerate(dom.operators)]
        hit = store[key] = GroundTask(dom.facts, dom.operators, fills, drop)
    return hit


def hadd_ids(
    grounder: Grounder, levels: LevelMap, drop: frozenset[str], cost: Callable[[Action], float]
) -> dict[int, float]:
    """Additive relaxed cost of each reachable fact id (true ones cost 0): one exploration of every action.

    A negative precondition whose atom is already false is free: it is settled at cost 0
    with the true facts (the values are those of a table of atoms, ``hadd_table``).
    """
    task = ground_task(grounder, drop)
    table_ids = grounder.domain.facts
    top = levels.top
    kept, waiting = task.kept(top)
    over: dict[int, tuple[tuple[int, int], ...]] = {}
    for k, lv in task.lowered(levels).items():
        over[k] = tuple((f, t) for f, c, t in task.pre[k] if c > lv)
    true_now = table_ids.ids_of(grounder.belief.atoms())
    settled = set(true_now)
    for pre in (kept, over.values()):
        for p in pre:
            for f, t in p:
                if t >= 0 and t not in true_now:
                    settled.add(f)  # already false
    n = task.n
    missing = [len(p) for p in kept]
    for k, p in over.items():
        missing[k] = len(p)
    extra: dict[int, list[int]] = {}
    for k, p in over.items():
        for f, _ in p:
            extra.setdefault(f, []).append(k)
    total = [0.0] * n
    fixed = task.fixed_cost
    for k in range(n):
        c = fixed[k]
        total[k] = cost(task.action(k)) if c is None else c
    table: dict[int, float] = {}
    queue: list[tuple[float, int, int]] = []
    tick = 0
    for f in settled:
        table[f] = 0.0
        queue.append((0.0, tick, f))
        tick += 1
    effects = task.effects
    for k in range(n):
        if missing[k] == 0:
            for e in effects[k]:
                if total[k] < table.get(e, math.inf):
                    table[e] = total[k]
                    queue.append((total[k], tick, e))
                    tick += 1
    heapq.heapify(queue)
    done: set[int] = set()
    while queue:
        c, _, f = heapq.heappop(queue)
        if f in done or c > table.get(f, math.inf):
            continue
        done.add(f)
        ready = [k for k in waiting.get(f, ()) if k not in over]  # overridden: their own preconditions
        ready.extend(extra.get(f, ()))
        for k in ready:
            missing[k] -= 1
            total[k] += c
            if missing[k] == 0:
                for e in effects[k]:
                    if total[k] < table.get(e, math.inf):
                        table[e] = total[k]
                        heapq.heappush(queue, (total[k], tick, e))
                        tick += 1
    return table


def hadd_table(
    grounder: Grounder, levels: LevelMap, drop: frozenset[str], cost: Callable[[Action], float]
) -> dict[Atom, float]:
    """:func:`hadd_ids` by atom (false atoms that are free left out)."""
    atoms = grounder.domain.facts.atoms
    return {atoms[f]: v for f, v in hadd_ids(grounder, levels, drop, cost).items()
            if not (atoms[f].value is False and v == 0.0)}
