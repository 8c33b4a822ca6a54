"""The relaxed estimates explored on demand (heuristics.LazyRelaxed)."""

from __future__ import annotations

import heapq
import math
import random
from pathlib import Path

import pytest

from nowplan.core.atoms import Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Generator, Operator, Precondition, reads_nothing
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.grounding import Grounder
from nowplan.planning.heuristics import hadd_table
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"


def _search(prob, state, heuristic: str, lazy: bool = True, levels: LevelMap | None = None) -> _Search:
    cfg = PlannerConfig(heuristic=heuristic, lazy_relaxation=lazy)
    return _Search(prob.domain, prob.objects, state, levels or flat_levels(), cfg, None)


def _state_space(prob, limit: int = 100_000):
    """Successors of every reachable state (of the first ``limit`` states reached; the others a sink)."""
    g = Grounder(prob.domain, prob.objects, prob.init)
    acts = [op.instantiate(b) for op in prob.domain.operators for b in g._fill(op, {})]
    succ: dict[State, list[State]] = {}
    frontier, seen = [prob.init], {prob.init}
    while frontier:
        s = frontier.pop(0)
        if len(succ) >= limit:
            succ[s] = []
            continue
        succ[s] = []
        for a in acts:
            if all(prob.domain.holds(p, s) for p in a.preconditions()):
                t = s.apply(a.effects())
                succ[s].append(t)
                if t not in seen:
                    seen.add(t)
                    frontier.append(t)
    return succ


def _distances(succ, start) -> dict[State, float]:
    dist = {start: 0.0}
    heap = [(0.0, 0, start)]
    tick = 1
    while heap:
        d, _, s = heapq.heappop(heap)
        if d > dist[s]:
            continue
        for t in succ[s]:
            if d + 1 < dist.get(t, math.inf):
                dist[t] = d + 1
                heapq.heappush(heap, (d + 1, tick, t))
                tick += 1
    return dist


@pytest.mark.parametrize("domain,problem", [("blocksworld", "p02"), ("gripper", "p01"), ("logistics", "p01")])
def test_hmax_and_lmcut_are_admissible_on_every_sampled_state(domain, problem):
    """h_max(G) <= LM-cut(G) <= the true distance from a reachable state s to a G state."""
    prob = load_pddl(DATA / domain / "domain.pddl", DATA / domain / f"{problem}.pddl")
    succ = _state_space(prob, limit=3000)
    states = sorted(succ, key=repr)
    rng = random.Random(0)
    checked = stronger = 0
    for s in rng.sample(states, 8):
        dist = _distances(succ, s)
        hmax, lmcut = _search(prob, s, "hmax"), _search(prob, s, "lmcut")
        for _ in range(15):
            target = rng.choice(states)
            atoms = rng.sample(list(target.atoms()), min(4, len(list(target.atoms()))))
            best = min((d for t, d in dist.items() if all(prob.domain.holds(a, t) for a in atoms)), default=math.inf)
            h1 = hmax.h(hmax.table.ids_of(atoms))
            h2 = lmcut.h(lmcut.table.ids_of(atoms))
            assert h1 <= h2 <= best, (s, atoms, h1, h2, best)
            stronger += h2 > h1
            checked += 1
    assert checked == 120 and stronger > 0


@pytest.mark.parametrize("problem", ["p01", "p02", "p03"])
def test_lazy_hadd_equals_the_ground_hadd_table(problem):
    """Explored on demand from each atom, h_add is the table of one exploration of every action."""
    prob = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / f"{problem}.pddl")
    for levels in (flat_levels(), LevelMap(0)):
        srch = _search(prob, prob.init, "hadd", levels=levels)
        table = hadd_table(srch.grounder, levels, srch.drop, srch.cost)
        g = Grounder(prob.domain, prob.objects, prob.init)
        every = {p.atom.bind(b) for op in prob.domain.operators for b in g._fill(op, {})
                 for p in op.preconditions} | set(table)
        for a in sorted(every, key=str):
            if a.predicate in srch.drop:
                continue
            want = 0.0 if srch.holds(a) else table.get(a, math.inf)
            assert srch.relaxed.value(srch.table.id(a)) == want, a


def test_hff_counts_an_action_two_atoms_need_once():
    preds = {n: Predicate(n, 0) for n in ("fuel", "a", "b")}
    ops = (
        Operator("refuel", (), (), (atom("fuel"),), cost=5.0),
        Operator("doa", (), (Precondition(atom("fuel")),), (atom("a"),), cost=1.0),
        Operator("dob", (), (Precondition(atom("fuel")),), (atom("b"),), cost=1.0),
    )
    dom = Domain("fuel", preds, ops)

    class P:
        domain, objects = dom, {}

    s = State([])
    both = [atom("a"), atom("b")]
    hadd, hff, hmax = (_search(P, s, h) for h in ("hadd", "hff", "hmax"))
    assert hadd.h(hadd.table.ids_of(both)) == 12.0  # fuel counted twice
    assert hff.h(hff.table.ids_of(both)) == 7.0  # once: the relaxed plan refuel, doa, dob
    assert hmax.h(hmax.table.ids_of(both)) == 6.0


def _gen_domain(reads):
    """``go(?to)`` gets its place from a generator; the place is only reachable from ``home``."""
    to = Var("to")
    preds = {"at": Predicate("at", 1), "ok": Predicate("ok", 1)}

    def where(b, goal, belief, ctx):
        yield {to: "home"}

    ops = (
        Operator("go", (to,), (Precondition(atom("ok", to)),), (atom("at", to),),
                 generators=(Generator("where", (to,), where, reads=reads),)),
    )
    return Domain("g", preds, ops)


def test_an_atom_left_unreached_is_a_dead_end_only_when_no_generator_read_the_goal():
    for reads, dead in ((reads_nothing, True), (None, False), (lambda b, g: len(g), False)):
        dom = _gen_domain(reads)

        class P:
            domain, objects = dom, {"home": None, "far": None}

        srch = _search(P, State([]), "hmax")
        h = srch.h(srch.table.ids_of([atom("at", "far")]))
        assert (h == math.inf) is dead, (reads, h)


def test_marsupial_hpn_plans_the_same_first_plan_with_every_relaxed_estimate():
    from nowplan.domains.marsupial.model import PLANNER
    from nowplan.domains.marsupial.scenarios import episode
    from dataclasses import replace

    costs = {}
    for h in ("count", "hmax", "hff"):
        ep = episode("single", 4, 0)
        cfg = replace(PLANNER, heuristic=h, lazy_relaxation=h != "count")
        res = plan(ep.problem.domain, ep.problem.objects, ep.belief, ep.problem.goal, None, cfg)
        assert res.solved and res.plan is not None
        costs[h] = (res.plan.cost(ep.belief), res.expanded)
    assert costs["hmax"][0] == costs["count"][0] == costs["hff"][0]
    assert costs["hmax"][1] < costs["count"][1] and costs["hff"][1] < costs["count"][1]


def test_lmcut_adds_up_over_independent_facts_as_the_whole_cut_does():
    """LM-cut over groups of goal facts whose relevant actions do not overlap equals LM-cut of the union."""
    prob = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p03.pddl")
    rng = random.Random(5)
    places = ("city1-loc1", "city2-airport", "city3-loc1", "city3-airport")
    atoms = sorted({a for a in prob.goal.atoms} | {atom("at", p, q) for p in ("pkg1", "pkg2", "pkg3")
                                                   for q in places}, key=str)
    parts = 0
    for levels in (flat_levels(), LevelMap(0)):
        srch = _search(prob, prob.init, "lmcut", levels=levels)
        r = srch.relaxed
        assert r is not None
        for _ in range(40):
            fs = srch.table.ids_of(rng.sample(atoms, rng.randint(1, 4)))
            h = srch.h(fs)
            goal = [f for f in fs if r.val.get(f, 0.0) > 0.0]
            assert all(r.val.get(f, math.inf) < math.inf for f in fs)
            whole = r._lmcut(goal) if goal else 0.0
            assert h == whole, (fs, h, whole)
            parts += len(r._parts(goal)) > 1 if goal else 0
    # marsupial's top level: each package's route has its own actions
    from nowplan.domains.marsupial.model import PLANNER
    from nowplan.domains.marsupial.scenarios import episode

    ep = episode("both", 4, 0)
    dom = ep.problem.domain
    srch = _Search(dom, ep.problem.objects, ep.belief, LevelMap(dom.top_level), PLANNER, None)
    r = srch.relaxed
    assert r is not None and r.kind == "lmcut"
    goal_atoms = sorted(ep.problem.goal.atoms)
    for k in range(1, len(goal_atoms) + 1):
        fs = srch.table.ids_of(goal_atoms[:k])
        h = srch.h(fs)
        goal = [f for f in fs if r.val.get(f, 0.0) > 0.0]
        assert h == r._lmcut(goal) > 0.0
        parts += len(r._parts(goal)) > 1
    assert parts >= 3
