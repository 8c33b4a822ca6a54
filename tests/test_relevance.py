"""Backward relevance (planning/relevance.py) and the groundings it restricts (task_grounding.py).

The lifted relevance over typed literal classes must contain every operator of a ground
action that ground backward relevance finds (from the goal through the preconditions each
action keeps at the level), on the classical domains at every level of their automatic
hierarchy and random goals; a task restricted to the relevant operators must be solvable
wherever the full one is, with plans that replay in the full task; a run's later calls
extend a grounding rather than ground again.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import relevance, task_grounding
from nowplan.planning.problem_hierarchy import prepare_problem
from nowplan.planning.forward import forward_plan
from nowplan.planning.relevance import relevant_operators
from nowplan.planning.task_grounding import grounding

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
DOMAINS = ["miconic", "zenotravel", "satellite", "logistics", "driverlog", "gripper", "depots", "rovers"]


def problem(name: str, k: int = 1) -> Problem:
    return prepare_problem(load_pddl(CLASSICAL / name / "domain.pddl", CLASSICAL / name / f"p0{k}.pddl", "auto"))


def ground_relevant(actions: list[Action], goal: Goal, level: int, statics: frozenset[str]) -> set[Action]:
    """Ground backward relevance: the actions adding a goal literal or a kept precondition of one."""
    by_effect: dict[Atom, list[Action]] = {}
    for a in actions:
        for e in a.effects():
            by_effect.setdefault(e, []).append(a)
    todo = [g for g in goal.atoms if g.predicate not in statics]
    seen, out = set(todo), set()
    while todo:
        for a in by_effect.get(todo.pop(), ()):
            if a not in out:
                out.add(a)
                for p in a.preconditions(level):
                    if p.predicate not in statics and p not in seen:
                        seen.add(p)
                        todo.append(p)
    return out


@pytest.fixture
def every_pruning(monkeypatch: pytest.MonkeyPatch) -> None:
    """Prune whatever is irrelevant, however little (not only where it pays)."""
    monkeypatch.setattr(relevance, "MOST", 2.0)


@pytest.mark.parametrize("name", DOMAINS)
def test_lifted_relevance_contains_ground_relevance(name: str, every_pruning: None) -> None:
    p = problem(name)
    statics = p.domain.static_predicates
    rng = random.Random(name)
    actions = grounding(p.domain, p.objects, p.init, -1).actions
    reachable = sorted({e for a in actions for e in a.effects() if e.value is True}, key=repr)
    for level in range(-1, p.domain.top_level + 1):
        goals = [p.goal, *(Goal.of(rng.sample(reachable, min(3, len(reachable)))) for _ in range(5))]
        for goal in goals:
            ops = relevant_operators(p.domain, p.objects, goal, level)
            names = {op.name for op in p.domain.operators} if ops is None else ops
            need = {a.name for a in ground_relevant(actions, goal, level, statics)}
            assert need <= names, (name, level, goal, need - names)


def test_an_abstract_level_of_miconic_needs_no_lift_moves() -> None:
    p = problem("miconic")
    top = p.domain.top_level
    assert top >= 1
    ops = relevant_operators(p.domain, p.objects, p.goal, top)
    assert ops is not None and {"up", "down"}.isdisjoint(ops) and {"board", "depart"} <= ops
    assert relevant_operators(p.domain, p.objects, p.goal, -1) is None  # concretely, everything


def _replays(p: Problem, plan: list[Action], goal: Goal, levels: LevelMap) -> bool:
    state = {a for a in p.init.atoms() if a.value is True}
    for a in plan:
        for pre in a.preconditions(levels.level(a)):
            held = pre in state if pre.value is True else pre.negate() not in state
            if not held:
                return False
        for e in a.effects():
            if e.value is True:
                state.add(e)
            else:
                state.discard(e.negate())
    return all((g in state) if g.value is True else (g.negate() not in state) for g in goal.atoms)


@pytest.mark.parametrize("name", ["miconic", "zenotravel", "satellite", "driverlog", "gripper"])
def test_restricted_tasks_solve_what_the_full_task_solves(name: str, every_pruning: None) -> None:
    p = problem(name)
    for level in range(p.domain.top_level, -1, -1):
        levels = LevelMap(level)
        task_grounding._CACHE.clear()
        res, steps = forward_plan(p.domain, p.objects, p.init, p.goal, levels, lambda a: a.cost(p.init))
        assert steps is not None, (name, level, res.status)
        plan = [a for a, _ in steps if a is not None]
        assert _replays(p, plan, p.goal, levels)
        ops = relevant_operators(p.domain, p.objects, p.goal, level)
        if ops is not None:
            assert {a.name for a in plan} <= ops
        # its pre-images hold where the plan is: the first in the initial state
        assert p.domain.satisfies(p.init, steps[0][1])


def test_little_pruning_keeps_every_operator() -> None:
    p = problem("satellite")
    types = {**dict(p.domain.constants), **dict(p.objects)}
    names = {op.name for op in p.domain.operators}
    sizes = {op.name: len(p.objects) ** len(op.params) for op in p.domain.operators}  # (an upper bound)
    smallest = min(sizes, key=lambda n: sizes[n])
    assert relevance._most(p.domain, types, names)
    assert not relevance._most(p.domain, types, {smallest})
    # all but the operator with the fewest typed instances: most of the instances, nothing pruned
    few = {op.name: op for op in p.domain.operators}
    counts = {n: relevance._most(p.domain, types, names - {n}) for n in few}
    assert any(counts.values()) and not all(counts.values())


def test_a_grounding_grows_and_keeps_its_actions() -> None:
    p = problem("miconic")
    top = p.domain.top_level
    task_grounding._CACHE.clear()
    few = relevant_operators(p.domain, p.objects, p.goal, top)
    assert few is not None
    small = grounding(p.domain, p.objects, p.init, top, few)
    assert {a.name for a in small.actions} <= few
    again = grounding(p.domain, p.objects, p.init, top, frozenset({"board"}))
    assert again is small  # a grounding of more operators serves
    full = grounding(p.domain, p.objects, p.init, top, None)
    assert {a.name for a in full.actions} == {op.name for op in p.domain.operators}
    mine = {a.key: a for a in full.actions}
    assert all(mine[a.key] is a for a in small.actions)  # extended: the same action objects
    task_grounding._CACHE.clear()
    assert sorted(a.key for a in full.actions) == sorted(a.key for a in grounding(p.domain, p.objects, p.init, top).actions)
