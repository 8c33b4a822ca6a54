"""Property tests on random small STRIPS problems built directly in the core model.

Ground truth is breadth-first search over the (tiny) state space.  Checked:
every plan the regression planner returns replays from the initial state to
the goal with each pre-image g(i) holding after step i, and each g(i-1) is
the independent regression of g(i) (tests/strips_model.py); the
planner finds a plan exactly when one exists, with and without inferred
mutexes; the inferred mutex groups hold in every reachable state; and with
all criticalities equal, planning at the HPN top level and flat planning agree.

The plans here are short (0-2 steps; the point is completeness against BFS);
tests/test_planner_property.py checks the plan contract on long plans.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, replace

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom, Goal, Var
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action, Operator, Precondition
from nowplan.core.state import State
from nowplan.errors import ContradictoryGoalError
from nowplan.planning.invariants import infer_mutexes, initially_valid, mutex_rule
from nowplan.planning.plan import Plan
from nowplan.planning.regression import PlannerConfig, plan
from tests.strips_model import level_of, regress, statics

OBJECTS = ("a", "b")
X = Var("x")


@dataclass(frozen=True)
class Case:
    domain: Domain
    init: State
    goal_atoms: tuple[Atom, ...]


@st.composite
def cases(draw: st.DrawFn) -> Case:
    arities = draw(st.lists(st.sampled_from([0, 1]), min_size=2, max_size=4))
    preds = {f"p{i}": Predicate(f"p{i}", k) for i, k in enumerate(arities)}
    crit = draw(st.integers(1, 3))

    def literal(lifted: bool) -> Atom:
        name = draw(st.sampled_from(sorted(preds)))
        if preds[name].arity == 0:
            return Atom(name, ())
        arg = draw(st.sampled_from([X, *OBJECTS] if lifted else list(OBJECTS)))
        return Atom(name, (arg,))

    ops = []
    for i in range(draw(st.integers(1, 4))):
        lifted = draw(st.booleans())
        pre = {literal(lifted) for _ in range(draw(st.integers(0, 2)))}
        pre_lits = tuple(
            Precondition(a if draw(st.booleans()) else a.negate(), crit) for a in sorted(pre, key=repr)
        )
        adds = {literal(lifted) for _ in range(draw(st.integers(1, 2)))}
        dels = {literal(lifted) for _ in range(draw(st.integers(0, 2)))} - adds
        effects = tuple(sorted((d.negate() for d in dels), key=repr)) + tuple(sorted(adds, key=repr))
        params = (X,) if lifted and any(X in a.args for a in [*pre, *adds, *dels]) else ()
        ops.append(Operator(f"op{i}", params, pre_lits, effects))
    domain = Domain("random", preds, tuple(ops))
    ground = all_atoms(domain)
    init = State(a for a in ground if draw(st.booleans()))
    # goal literals mostly disagree with the initial state, so most cases need a plan
    goal = tuple(
        Atom(a.predicate, a.args, not init.holds(a) if draw(st.integers(0, 3)) else draw(st.booleans()))
        for a in draw(st.lists(st.sampled_from(ground), min_size=1, max_size=3, unique=True))
    )
    return Case(domain, init, goal)


def all_atoms(domain: Domain) -> list[Atom]:
    out = []
    for p in domain.predicates.values():
        out += [Atom(p.name, args) for args in itertools.product(OBJECTS, repeat=p.arity)]
    return out


def ground_actions(domain: Domain) -> list[Action]:
    return [
        op.instantiate(dict(zip(op.params, vals, strict=True)))
        for op in domain.operators
        for vals in itertools.product(OBJECTS, repeat=len(op.params))
    ]


def applicable(domain: Domain, a: Action, s: State) -> bool:
    return all(domain.holds(p, s) for p in a.preconditions())


def reachable(case: Case) -> set[State]:
    acts = ground_actions(case.domain)
    seen, frontier = {case.init}, [case.init]
    while frontier:
        s = frontier.pop()
        for a in acts:
            if applicable(case.domain, a, s):
                t = s.apply(a.effects())
                if t not in seen:
                    seen.add(t)
                    frontier.append(t)
    return seen


def replays(domain: Domain, init: State, p: Plan, goal: Goal) -> None:
    stat = statics(domain)
    for i, a in enumerate(p.actions, start=1):  # mutex rules only make a regression fail
        assert set(p.preimage(i - 1).atoms) == regress(p.preimage(i).atoms, a, level_of(p.levels, a), stat)
    state = init
    assert domain.satisfies(state, p.preimage(0))
    for i, a in enumerate(p.actions, start=1):
        assert applicable(domain, a, state), f"step {i} {a} not applicable"
        state = state.apply(a.effects())
        assert domain.satisfies(state, p.preimage(i)), f"g({i}) fails after {a}"
    assert domain.satisfies(state, goal)


CONFIG = PlannerConfig(max_nodes=20_000, time_limit=20, seed=0)
OBJ = {o: None for o in OBJECTS}


@pytest.mark.timeout(120, method="thread")  # a planner loop fails the run (see pyproject.toml)
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(cases(), st.booleans())
def test_regression_is_sound_and_complete_on_random_strips(case: Case, shortcuts: bool) -> None:
    domain = case.domain
    states = reachable(case)
    solvable = any(domain.satisfies(s, case.goal_atoms) for s in states)
    config = replace(CONFIG, serialization=shortcuts, monotonic=shortcuts)
    try:
        goal = Goal.of(case.goal_atoms, domain.rules)
    except ContradictoryGoalError:
        assert not solvable
        return
    flat = plan(domain, OBJ, case.init, goal, flat_levels(), config)
    assert flat.solved == solvable, (flat.status, flat.reason)
    if flat.plan is not None:
        replays(domain, case.init, flat.plan, goal)
    # all criticalities are equal: the HPN top level keeps every precondition
    top = plan(domain, OBJ, case.init, goal, LevelMap(domain.top_level), config)
    assert top.solved == flat.solved
    if top.plan is not None:
        assert all(top.plan.is_primitive(i) for i in range(1, len(top.plan) + 1))
        replays(domain, case.init, top.plan, goal)

    # inferred mutexes are sound: they hold everywhere, and planning with them agrees
    groups = infer_mutexes(domain, case.init)
    for g in groups:
        assert all(initially_valid(g, s.atoms()) for s in states), g
    if groups:
        dm = replace(domain, conflicts=(mutex_rule(groups),))
        try:
            goal_m = Goal.of(case.goal_atoms, dm.rules)
        except ContradictoryGoalError:
            assert not solvable
            return
        with_m = plan(dm, OBJ, case.init, goal_m, flat_levels(), config)
        assert with_m.solved == solvable
        if with_m.plan is not None:
            replays(dm, case.init, with_m.plan, goal_m)
