"""The landmark graph's first achievers found by one labelled propagation (lm_orders.prime_first_achievers).

Reference: the exploration per fact set in ``lm_orders.first_achievers`` (the
relaxation run once per set with the set's adders left out).  The propagation
must give the same actions for every set, and the landmark graph (sets,
necessary and reasonable orderings) must be the same as when every set is
explored on its own.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, cast

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Action
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import landmarks
from nowplan.planning.landmarks import LandmarkCount, landmark_sets
from nowplan.planning.lm_orders import first_achievers, prime_first_achievers
from nowplan.planning.task import Task, build_task

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
PREDICATES = ("p", "q", "r")


def _task(nfacts: int, actions: list[tuple[list[int], list[int], list[int]]], init: list[int],
          goal: list[int], mutex_mod: int) -> Task:
    """A task in build_task's form; facts of three predicates, so that disjunctive landmarks occur."""
    pre = [tuple(sorted(set(p))) for p, _, _ in actions]
    add = [tuple(sorted(set(a))) for _, a, _ in actions]
    dele = [tuple(sorted(set(d) - set(a))) for (_, _, d), a in zip(actions, add, strict=True)]
    facts = [Atom(PREDICATES[i % 3], (f"o{i}",)) for i in range(nfacts)]
    task = Task(facts, {a: i for i, a in enumerate(facts)}, cast(list[Action], list(range(len(actions)))),
                pre, add, dele, [1.0] * len(actions), frozenset(init), tuple(sorted(set(goal))))
    task.index_preconditions()
    if mutex_mod:
        task.memo["mutex"] = lambda f, g: f != g and (f + g) % mutex_mod == 0
    return task


@st.composite
def tasks(draw: st.DrawFn) -> Task:
    n = draw(st.integers(1, 14))
    fact = st.integers(0, n - 1)
    ids = st.lists(fact, max_size=3)
    pre = st.one_of(st.lists(fact, min_size=1, max_size=2), ids)
    actions = draw(st.lists(st.tuples(pre, st.lists(fact, min_size=1, max_size=3), ids), max_size=12))
    # "t by x or by y" with x and y facts of one predicate: a disjunctive landmark when t is a landmark
    targets: set[int] = set()
    sides: set[int] = set()
    side_pre = st.lists(fact, max_size=1)
    for t, x, k, px, py in draw(st.lists(st.tuples(fact, fact, st.integers(1, 3), side_pre, side_pre), max_size=3)):
        y = x + 3 * k
        if y < n:
            actions += [([x], [t], []), ([y], [t], []), (px, [x], []), (py, [y], [])]
            targets.add(t)
            sides |= {x, y}
    init = [f for f in draw(st.lists(fact, min_size=1, max_size=3)) if f not in sides]
    reach, grew = set(init), True
    while grew:  # mostly goals the relaxation reaches (else there is no landmark graph to compare)
        grew = False
        for p, a, _ in actions:
            if set(p) <= reach and not set(a) <= reach:
                reach |= set(a)
                grew = True
    candidates = sorted(reach - set(init)) or list(range(n))
    goal = draw(st.lists(st.sampled_from(candidates), min_size=1, max_size=3))
    goal += sorted(targets & reach)[: draw(st.integers(0, 2))]
    return _task(n, actions, init, goal,
                 draw(st.sampled_from([0, 2, 3, 5])))


def _explored(task: Task, facts: frozenset[int]) -> list[int]:
    """The reference: one exploration for ``facts`` (nothing memoised)."""
    task.memo.pop("first_achievers", None)
    return first_achievers(task, facts)


def _graph(lc: LandmarkCount) -> tuple[Any, ...]:
    return (lc.sets, sorted((k, sorted(v)) for k, v in lc.before.items()),
            sorted((k, sorted(v)) for k, v in lc.reasonable.items()), lc.unreachable)


def _both_graphs(make: Any, monkeypatch: pytest.MonkeyPatch) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    """The graph as built, and as built by the plain algorithm: every set explored on its own and the
    mutex asked for every pair (a plain function: no short cut for facts in no invariant group)."""
    fast = _graph(LandmarkCount(make()))
    slow_task = make()
    mutex = slow_task.memo.get("mutex")
    if mutex is not None:
        slow_task.memo["mutex"] = lambda f, g: mutex(f, g)
    with monkeypatch.context() as m:
        m.setattr(landmarks, "prime_first_achievers", lambda *args: None)
        slow = _graph(LandmarkCount(slow_task))
    return fast, slow


@settings(max_examples=400, deadline=None)
@given(task=tasks(), data=st.data())
def test_propagation_finds_the_explored_first_achievers(task: Task, data: st.DataObject) -> None:
    n = len(task.facts)
    families = data.draw(st.lists(st.frozensets(st.integers(0, n - 1), min_size=1, max_size=4), max_size=6))
    lm = landmark_sets(task)
    expected = {f: _explored(task, f) for f in families}
    task.memo.pop("first_achievers", None)
    prime_first_achievers(task, families, lm)
    memo = task.memo["first_achievers"]
    assert {f: list(memo[f]) for f in families} == expected


@settings(max_examples=300, deadline=None)
@given(task=tasks())
def test_random_tasks_keep_the_same_landmark_graph(task: Task) -> None:
    def copy() -> Task:
        t = Task(task.facts, task.index, task.actions, task.pre, task.add, task.dele, task.cost, task.init,
                 task.goal)
        t.index_preconditions()
        if "mutex" in task.memo:
            t.memo["mutex"] = task.memo["mutex"]
        return t

    with pytest.MonkeyPatch.context() as mp:
        fast, slow = _both_graphs(copy, mp)
    assert fast == slow


def _pddl(domain: str, problem: str) -> Task:
    p = load_pddl(CLASSICAL / domain / "domain.pddl", CLASSICAL / domain / problem)
    return build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: 1.0)


DOMAINS = sorted(d.name for d in CLASSICAL.iterdir() if (d / "domain.pddl").exists())


@pytest.mark.parametrize("domain", DOMAINS)
def test_classical_p05_keeps_the_same_landmark_graph(domain: str, monkeypatch: pytest.MonkeyPatch) -> None:
    fast, slow = _both_graphs(lambda: _pddl(domain, "p05.pddl"), monkeypatch)
    assert fast == slow


@pytest.mark.slow
@pytest.mark.parametrize("problem", ["p01.pddl", "p02.pddl", "p03.pddl", "p04.pddl"])
@pytest.mark.parametrize("domain", DOMAINS)
def test_every_classical_instance_keeps_the_same_landmark_graph(domain: str, problem: str,
                                                                monkeypatch: pytest.MonkeyPatch) -> None:
    fast, slow = _both_graphs(lambda: _pddl(domain, problem), monkeypatch)
    assert fast == slow


def test_gripper_disjunction_and_initial_fact_are_found_once() -> None:
    task = _pddl("gripper", "p01.pddl")
    carry = frozenset(i for i, a in enumerate(task.facts) if a.predicate == "carry" and a.args[0] == "ball1")
    robby_a = frozenset(i for i, a in enumerate(task.facts) if str(a) == "at-robby(rooma)")
    assert robby_a <= task.init
    prime_first_achievers(task, [carry, robby_a], landmark_sets(task))
    memo = task.memo["first_achievers"]
    assert {task.actions[a].pddl() for a in memo[carry]} == {"(pick ball1 rooma left)", "(pick ball1 rooma right)"}
    # at-robby(rooma) holds now; moving back from room B needs the robot to have left room A first
    assert memo[robby_a] == ()
    assert {f: list(memo[f]) for f in (carry, robby_a)} == {f: _explored(task, f) for f in (carry, robby_a)}
