"""regress_chain (incremental conflict checks) gives what regress_through (every pre-image checked from
scratch) gives: the same goals and the same failing step, on forward plans of the classical instances and
on random action sequences (most of which fail somewhere), from the problem's goal or a random part of a
reachable state."""

from __future__ import annotations

import random
from functools import cache
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Goal
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.preimage import regress_through, static_drop
from nowplan.planning.preimage_chain import regress_chain
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.task_grounding import grounding

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
DOMAINS = ["logistics", "zenotravel", "driverlog", "depots", "miconic", "satellite", "gripper", "barman",
           "rovers", "blocksworld", "nomystery", "visitall", "floortile"]


@cache
def _problem(name: str, k: int):  # type: ignore[no-untyped-def]
    p = load_pddl(CLASSICAL / name / "domain.pddl", CLASSICAL / name / f"p0{k}.pddl")
    acts = sorted(grounding(p.domain, p.objects, p.init, -1).actions, key=lambda a: (a.name, repr(a.args)))
    return p, acts


def _same(p, goal: Goal, actions: list[Action], levels: LevelMap) -> None:  # type: ignore[no-untyped-def]
    drop = static_drop(p.domain, p.init)
    assert regress_chain(goal, actions, levels, p.domain, drop) == \
        regress_through(goal, actions, levels, p.domain, drop)


@pytest.mark.parametrize("name", DOMAINS)
def test_forward_plans_regress_the_same(name: str) -> None:
    p, _ = _problem(name, 3)
    res = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), PlannerConfig(engine="forward"))
    assert res.plan is not None and len(res.plan.actions) > 2
    _same(p, p.goal, list(res.plan.actions), flat_levels())
    if p.domain.top_level > 0:
        _same(p, p.goal, list(res.plan.actions), LevelMap(p.domain.top_level))


@settings(max_examples=60, deadline=None)
@given(st.sampled_from(DOMAINS), st.integers(1, 2), st.integers(0, 2**16), st.integers(1, 12),
       st.booleans())
def test_random_sequences_regress_the_same(name: str, k: int, seed: int, length: int, own_goal: bool) -> None:
    p, acts = _problem(name, k)
    rng = random.Random(seed)
    # a walk of applicable actions (regresses) with now and then a random one (usually fails)
    state = p.init
    seq: list[Action] = []
    for _ in range(length):
        ok = [a for a in acts if all(p.domain.holds(c, state) for c in a.preconditions())]
        a = rng.choice(ok) if ok and rng.random() < 0.8 else rng.choice(acts)
        seq.append(a)
        state = state.apply(a.effects())
    if own_goal:
        goal = p.goal
    else:
        true = sorted((a for a in state.atoms() if a.value is True), key=repr)
        goal = Goal(frozenset(rng.sample(true, min(len(true), rng.randint(1, 8)))))  # may clash: then the fallback
    _same(p, goal, seq, flat_levels())


@pytest.mark.parametrize("name", DOMAINS)
def test_one_step_against_every_true_atom(name: str) -> None:
    """Every action (one step) from a goal of one atom true initially: the clashes of an action's effects
    with a goal atom it leaves alone, which a longer sequence's preconditions often catch as well."""
    p, acts = _problem(name, 2)
    true = sorted((a for a in p.init.atoms() if a.value is True), key=repr)[:60]
    rng = random.Random(0)
    outcomes = set()
    for act in rng.sample(acts, min(len(acts), 150)):
        for atom in true:
            drop = static_drop(p.domain, p.init)
            got = regress_chain(Goal(frozenset((atom,))), [act], flat_levels(), p.domain, drop)
            assert got == regress_through(Goal(frozenset((atom,))), [act], flat_levels(), p.domain, drop)
            outcomes.add(got[1] is None)
    assert outcomes == {True, False} or name in ("visitall", "miconic", "gripper", "blocksworld", "barman",
                                                 "floortile", "rovers", "satellite", "nomystery")


def test_an_effect_clashing_with_a_goal_atom_it_leaves_alone() -> None:
    """A declared at-most-one group and an action that enters it with no precondition in it: only the
    effect check of the step finds the clash (PDDL's inferred groups always pair an add with a needed
    delete, so the preconditions find it there as well)."""
    from nowplan.core.atoms import AtMostOne, Var, atom
    from nowplan.core.domain import Domain, Predicate
    from nowplan.core.operators import Operator, Precondition

    x, y = Var("x"), Var("y")
    preds = {"at": Predicate("at", 2), "lit": Predicate("lit", 1)}
    ops = (Operator("jump", (y,), (), (atom("at", "r", y),)),
           Operator("go", (x, y), (Precondition(atom("at", "r", x), 1),),
                    (atom("at", "r", y), atom("at", "r", x, value=False))),
           Operator("light", (x,), (Precondition(atom("at", "r", x), 1),), (atom("lit", x),)))
    dom = Domain("jumps", preds, ops, conflicts=(AtMostOne(("at",)),))  # one place per first argument
    byname = {o.name: o for o in ops}
    rng = random.Random(1)
    rooms = "abc"
    outcomes = set()
    for _ in range(300):
        seq = []
        for _ in range(rng.randint(1, 4)):
            name = rng.choice(["jump", "go", "light"])
            args = (rng.choice(rooms),) if name != "go" else tuple(rng.sample(rooms, 2))
            seq.append(Action(byname[name], args))
        goal = Goal(frozenset(rng.sample([atom("at", "r", rng.choice(rooms)), atom("lit", "a"), atom("lit", "b")],
                                         rng.randint(1, 2))))
        got = regress_chain(goal, seq, flat_levels(), dom, frozenset())
        assert got == regress_through(goal, seq, flat_levels(), dom, frozenset())
        outcomes.add(got[1] is None)
    assert outcomes == {True, False}
