"""The landmark graph built per call is the same as the frozen reference's (tests/lm_reference.py).

The reference is the construction as it was before the per-call speed-ups
(landmark sets over the whole task, first achievers by scanning every
action).  Compared: the fact landmarks, the landmark sets in order, the
necessary orderings, the reasonable orderings, the achievers, the goal flags
and reachability -- on every shipped PDDL problem, the classical benchmark
instances, HPN-like variants of them (most goal atoms already true, initial
states a few random steps in) and random tasks.
"""

from __future__ import annotations

import random
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from lm_reference import ReferenceLandmarkCount
from nowplan.core.levels import flat_levels
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.landmarks import LandmarkCount, landmark_sets
from nowplan.planning.axioms import relaxed_task
from nowplan.planning.hff import RelaxedHeuristic
from nowplan.planning.lm_orders import prime_first_achievers, relaxed_order
from nowplan.planning.task import Task, build_task
from test_lm_first_achievers import tasks

ROOT = Path(__file__).resolve().parents[1]
CLASSICAL = ROOT / "benchmarks" / "classical"
SHIPPED = ROOT / "src" / "nowplan" / "data" / "pddl"


def _copy(task: Task, init: frozenset[int] | None = None, goal: tuple[int, ...] | None = None) -> Task:
    """A fresh task (empty memo but the mutex) with the same actions."""
    t = Task(task.facts, task.index, task.actions, task.pre, task.add, task.dele, task.cost,
             task.init if init is None else init, task.goal if goal is None else goal, task.unsolvable,
             axioms=task.axioms)
    t.index_preconditions()
    if "mutex" in task.memo:
        t.memo["mutex"] = task.memo["mutex"]
    return t


def _graph(lc: Any) -> tuple[Any, ...]:
    return (lc.landmarks, lc.sets, lc.before, lc.reasonable, lc.achievers, lc.is_goal, lc.of_fact, lc.unreachable,
            lc.goal)


def _same(task: Task, orders: bool = True) -> None:
    old = _graph(ReferenceLandmarkCount(_copy(task), orders))
    assert _graph(LandmarkCount(_copy(task), orders)) == old
    t = _copy(task)
    native = RelaxedHeuristic(t).native
    if native is not None:  # the relaxed exploration by the kernel: the same order, the same graph
        expected = relaxed_order(_copy(relaxed_task(t)))
        assert native.relaxed_order(t.init)[0] == expected
        assert native.landmark_sets(t.init, expected) == landmark_sets(_copy(relaxed_task(t)))
        assert "relaxed_order" not in relaxed_task(t).memo
        assert _graph(LandmarkCount(t, orders, native)) == old
        assert relaxed_task(t).memo["relaxed_order"] == expected


def _variants(task: Task, seed: int) -> list[Task]:
    """The task, and HPN-like ones: a few random steps in, goals mostly true already."""
    rng = random.Random(seed)
    out = [task]
    if task.axioms:
        return out
    state = set(task.init)
    for _ in range(4):
        for _ in range(rng.randint(1, 6)):
            app = [a for a in range(len(task.pre)) if all(p in state for p in task.pre[a])]
            if not app:
                break
            a = rng.choice(app)
            state = (state - set(task.dele[a])) | set(task.add[a])
        init = frozenset(state)
        true_now = sorted(init)
        goal = set(rng.sample(true_now, min(len(true_now), rng.randint(0, 12))))
        goal |= set(rng.sample(list(task.goal), min(len(task.goal), rng.randint(0, 2))))
        out.append(_copy(task, init, tuple(sorted(goal))))
    return out


def _pddl(domain: Path, problem: Path) -> Task:
    p = load_pddl(domain, problem)
    return build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: 1.0)


SHIPPED_CASES = [(d.name, p.name) for d in sorted(SHIPPED.iterdir()) if d.is_dir()
                 for p in sorted(d.glob("p[0-9][0-9].pddl"))]
CLASSICAL_DOMAINS = sorted(d.name for d in CLASSICAL.iterdir() if (d / "domain.pddl").exists())


@pytest.mark.parametrize(("domain", "problem"), SHIPPED_CASES)
def test_shipped_problems_keep_the_graph(domain: str, problem: str) -> None:
    task = _pddl(SHIPPED / domain / "domain.pddl", SHIPPED / domain / problem)
    for k, t in enumerate(_variants(task, 1)):
        _same(t, orders=k != 1)


AXIOMS = Path(__file__).resolve().parent / "data" / "pddl_axioms"


@pytest.mark.parametrize("name", ["doors-p01", "doors-p02", "grid-p01", "grid-p02"])
def test_tasks_with_derived_predicates_keep_the_graph(name: str) -> None:
    task = _pddl(AXIOMS / f"{name.split('-')[0]}-domain.pddl", AXIOMS / f"{name}.pddl")
    assert task.axioms
    _same(task)


@pytest.mark.parametrize("domain", CLASSICAL_DOMAINS)
def test_classical_instances_keep_the_graph(domain: str) -> None:
    task = _pddl(CLASSICAL / domain / "domain.pddl", CLASSICAL / domain / "p02.pddl")
    for t in _variants(task, 2):
        _same(t)


@pytest.mark.slow
@pytest.mark.parametrize("problem", ["p01.pddl", "p03.pddl", "p04.pddl", "p05.pddl"])
@pytest.mark.parametrize("domain", CLASSICAL_DOMAINS)
def test_every_classical_instance_keeps_the_graph(domain: str, problem: str) -> None:
    task = _pddl(CLASSICAL / domain / "domain.pddl", CLASSICAL / domain / problem)
    for t in _variants(task, 3):
        _same(t)


@settings(max_examples=400, deadline=None)
@given(task=tasks(), data=st.data())
def test_random_tasks_keep_the_graph(task: Task, data: st.DataObject) -> None:
    # goals partly true now, as in most of HPN's calls
    extra = data.draw(st.lists(st.sampled_from(sorted(task.init)), max_size=3)) if task.init else []
    goal = tuple(sorted(set(task.goal) | set(extra)))
    _same(_copy(task, goal=goal), orders=data.draw(st.booleans()))


@settings(max_examples=300, deadline=None)
@given(task=tasks(), data=st.data())
def test_kernel_first_achievers_are_python_s(task: Task, data: st.DataObject) -> None:
    """The labelled propagation in C gives the Python propagation's first achievers (more than 64 sets too)."""
    native = RelaxedHeuristic(task).native
    if native is None:
        pytest.skip("no compiled kernel")
    n = len(task.facts)
    families = data.draw(st.lists(st.frozensets(st.integers(0, n - 1), min_size=1, max_size=4), max_size=6))
    families += [frozenset((f,)) for f in range(n)] * data.draw(st.sampled_from([0, 1]))
    families += [frozenset({f, (f * 7 + k) % n}) for f in range(n) for k in range(5)] * data.draw(st.sampled_from([0, 1]))
    py, c = _copy(task), _copy(task)
    prime_first_achievers(py, families, [])
    prime_first_achievers(c, families, [], native)
    assert c.memo["first_achievers"] == py.memo["first_achievers"]


@settings(max_examples=300, deadline=None)
@given(task=tasks(), data=st.data())
def test_kernel_landmark_sets_are_python_s(task: Task, data: st.DataObject) -> None:
    """Zhu and Givan's fixpoint in C gives the Python sets, over the whole task and over a goal's cone."""
    native = RelaxedHeuristic(task).native
    if native is None:
        pytest.skip("no compiled kernel")
    goal = data.draw(st.lists(st.integers(0, len(task.facts) - 1), max_size=3)) if data.draw(st.booleans()) else None
    assert landmark_sets(_copy(task), goal, native) == landmark_sets(_copy(task), goal)
