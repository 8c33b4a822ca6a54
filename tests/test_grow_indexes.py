"""Lookups that replaced per-call scans (issue 19 target 3): marsupial's where-is index, shared achievers."""

from __future__ import annotations

import random

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import atom
from nowplan.core.levels import LevelMap
from nowplan.core.state import State
from nowplan.domains.marsupial.model import PLANNER, Where, same_city_holds
from nowplan.domains.marsupial.problems import generate
from nowplan.planning.context import PlanningContext
from nowplan.planning.grounding import Grounder
from nowplan.planning.plan import Plan, PlanStep
from nowplan.planning.regression import plan


def _scan_same_city(belief, pkg, veh) -> bool:
    if belief.value(("in", (pkg, veh))):
        return True
    return any(x[0] == pkg and belief.value(("reachable", (x[1], veh))) for x in belief.facts("at"))


def _scan_place(belief, pkg):
    for args in belief.facts("at"):
        if args[0] == pkg:
            return str(args[1])
    for args in belief.facts("in"):
        if args[0] == pkg:
            return _scan_place(belief, str(args[1]))
    return None


def test_same_city_and_place_now_agree_with_a_scan_as_the_state_changes():
    prob, spec = generate("both", 6, 3)
    reach = {v: frozenset(x[0] for x in prob.init.facts("reachable") if x[1] == v)
             for v in {x[1] for x in prob.init.facts("reachable")}}
    where = Where(reach, spec.plane)
    vehicles = sorted(reach)
    packages = sorted(o for o, t in prob.objects.items() if t == "package")
    places = sorted({x[0] for x in prob.init.facts("reachable")})
    rng = random.Random(0)
    state = prob.init
    for _ in range(30):
        belief = SymbolicBelief(state)
        for pkg in packages:
            assert where.place_now(belief, pkg) == _scan_place(belief, pkg)
            for veh in vehicles:
                for value in (True, False):
                    assert same_city_holds(belief, (pkg, veh), value) == (_scan_same_city(belief, pkg, veh) == value)
        # move a package: onto the ground somewhere, or into a vehicle
        pkg = rng.choice(packages)
        here = [atom("at", pkg, x, value=False) for x in places] + [atom("in", pkg, v, value=False) for v in vehicles]
        there = atom("at", pkg, rng.choice(places)) if rng.random() < 0.6 else atom("in", pkg, rng.choice(vehicles))
        state = state.apply([*here, there])


def test_atoms_no_generator_can_achieve_share_their_achievers_across_calls():
    """Load (with a generator) clears at(p, l) but cannot make it true: at(p, l)'s achievers are shared."""
    prob, _ = generate("single", 3, 0)
    belief = SymbolicBelief(prob.init)
    g = Grounder(prob.domain, prob.objects, belief, None, 8, True)
    goal = prob.goal
    target = next(iter(goal.atoms))  # at(p, destination): only Unload makes it true
    first = g.achievers(target, goal)
    assert first and all(a.name == "unload" for a in first)
    assert g.shares_answer(target)
    again = Grounder(prob.domain, prob.objects, SymbolicBelief(prob.init), None, 8, True)
    assert again.achievers(target, goal) is first  # the same list: no grounding in the next call
    sc = atom("same_city", "p0", "truck0")  # SameCity's place comes from a generator that reads the goal
    assert not g.shares_answer(sc)


def test_sharing_changes_no_plan():
    prob, _ = generate("both", 4, 2)
    levels = LevelMap(prob.domain.top_level)
    plans = []
    for memo in (True, False):
        Grounder.memo = memo
        try:
            res = plan(prob.domain, prob.objects, SymbolicBelief(prob.init), prob.goal, levels, PLANNER)
        finally:
            Grounder.memo = True
        assert res.solved and res.plan is not None
        plans.append([s.action.key if s.action else None for s in res.plan.steps])
    assert plans[0] == plans[1]


def test_state_fixture_is_immutable():
    s = State([atom("at", "p0", "x")])
    assert s.facts("at") is s.facts("at")  # the index relies on one list per state


class _Own(SymbolicBelief):
    """A belief of a domain's own kind: it may answer from more than its state."""


def test_calls_from_one_state_share_tests_and_achievers():
    """Grounders on one plain state share a per-state store; another state, a subclass or a plan stack do not."""
    prob, _ = generate("both", 3, 0)
    d, objs = prob.domain, prob.objects
    a = Grounder(d, objs, SymbolicBelief(prob.init), None, 8, True)
    b = Grounder(d, objs, SymbolicBelief(prob.init), None, 8, True)
    assert a.per_state is not None and a.per_state is b.per_state
    sc = atom("same_city", "p0", "truck0")  # achieved with a generator that reads the goal
    first = a.achievers(sc, prob.goal)
    assert b.achievers(sc, prob.goal) is first  # grounded once for the state
    moved = prob.init.apply([atom("at", "p0", "c0-ap")])
    c = Grounder(d, objs, SymbolicBelief(moved), None, 8, True)
    assert c.per_state is not None and c.per_state is not a.per_state
    assert Grounder(d, objs, _Own(prob.init), None, 8, True).per_state is None
    stacked = PlanningContext((Plan((PlanStep(None, prob.goal),), LevelMap(4)),), {})
    assert Grounder(d, objs, SymbolicBelief(prob.init), stacked, 8, True).per_state is None
    other = PlanningContext((), {"forbidden_first": frozenset({("x", ())})})
    assert Grounder(d, objs, SymbolicBelief(prob.init), other, 8, True).per_state is not a.per_state
    for mutable in ([1], object(), {"k": 1}):  # a value whose state could change between calls: no store
        ctx = PlanningContext((), {"foresight": False, "x": mutable})
        assert Grounder(d, objs, SymbolicBelief(prob.init), ctx, 8, True).per_state is None
    assert Grounder(d, objs, SymbolicBelief(prob.init), None, 3, True).per_state is not a.per_state


def test_state_sharing_changes_no_episode(monkeypatch):
    """HPN's executed actions and planner calls are the same with the per-state store and without it."""
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode
    from nowplan.planning import grounding

    def run() -> tuple[object, ...]:
        ep = episode("both", 5, 1)
        m, _, ok = timed_run(ep, "hpn", 1, 120)
        return ok, m.actions, m.execution_cost, m.plans_made, ep.world.state

    shared = run()
    monkeypatch.setattr(grounding, "point_state", lambda belief: None)
    alone = run()
    assert shared[0] and shared == alone
