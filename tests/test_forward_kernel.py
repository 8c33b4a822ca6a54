"""The forward engine's compiled kernel against its Python reference.

The kernel (``nowplan.planning._kernel``, built on install when a C compiler
is present) must give exactly what the Python code gives: the same h and
preferred operators for every state, heuristic and cost type, and the same
search (status, plan, expanded, generated, evaluated) on the bundled PDDL
problems, a generated logistics problem and random small integer tasks, for
GBFS, A*, LAMA and the anytime improvement's bounded weighted A*.
``NOWPLAN_PURE_PYTHON=1`` selects the Python code; without a built kernel
the comparisons skip (the Python tests still run).
"""

from __future__ import annotations

import logging
import math
import random
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any, cast

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.levels import flat_levels
from nowplan.io.logistics_gen import generate_logistics
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import anytime, forward, native
from nowplan.planning.hff import RelaxedHeuristic
from nowplan.planning.plan import PlanStatus
from nowplan.planning.task import Task, build_task

from kernel_support import PDDL, PROBLEMS, int_task, int_tasks, needs_kernel, pddl_task

_cls, _why = native._load()

KINDS = ("ff", "add", "max")
COST_TYPES = ("plusone", "one", "normal")


def summary(res: forward.ForwardResult, task: Task) -> tuple[Any, ...]:
    plan = None if res.actions is None else [task.actions.index(a) for a in res.actions]
    return res.status, plan, res.expanded, res.generated, res.evaluated, res.reason


def both(mode: Callable[[str], None], task: Task, **kw: Any) -> tuple[tuple[Any, ...], tuple[Any, ...]]:
    out = []
    for m in ("python", "c"):
        mode(m)
        out.append(summary(forward.search(task, **kw), task))
    return out[0], out[1]


def walk_states(task: Task, n: int, seed: int) -> list[frozenset[int]]:
    """The initial state and states of random walks from it (restarting at dead ends)."""
    rng = random.Random(seed)
    succ = forward._Successors(task)
    states, s = [task.init], task.init
    for _ in range(n):
        acts = succ(s)
        s = task.init if not acts else forward._apply(task, s, rng.choice(acts))
        states.append(s)
    return states


def same_evaluations(mode: Callable[[str], None], task: Task, states: list[frozenset[int]]) -> None:
    for kind in KINDS:
        for ct in COST_TYPES:
            mode("c")
            h = RelaxedHeuristic(task, kind, ct)  # type: ignore[arg-type]
            assert h.native is not None
            for s in states:
                assert h.native.evaluate(s) == h.evaluate_py(s), (kind, ct, sorted(s))


# --------------------------------------------------------------------------- PDDL problems


@needs_kernel
@pytest.mark.parametrize(("domain", "problem"), PROBLEMS)
def test_pddl_heuristic_values_are_identical(mode: Callable[[str], None], domain: str, problem: str) -> None:
    task = pddl_task(domain, problem)
    same_evaluations(mode, task, walk_states(task, 60, seed=len(problem)))


@needs_kernel
@pytest.mark.parametrize(("domain", "problem"), PROBLEMS)
@pytest.mark.parametrize(("method", "kind"), [("gbfs", "ff"), ("gbfs", "add"), ("astar", "ff"), ("astar", "max"),
                                              ("lama", "ff")])
def test_pddl_searches_are_identical(mode: Callable[[str], None], domain: str, problem: str, method: str,
                                     kind: str) -> None:
    task = pddl_task(domain, problem)
    py, c = both(mode, task, method=method, heuristic=kind, max_nodes=3000)
    assert py == c
    assert py[0] in (PlanStatus.SOLVED, PlanStatus.NODE_LIMIT)
    if kind == "ff":
        assert py[0] is PlanStatus.SOLVED


@needs_kernel
def test_generated_logistics_search_is_identical(mode: Callable[[str], None], tmp_path: Path) -> None:
    prob = tmp_path / "l8.pddl"
    prob.write_text(generate_logistics(6, 3, 2, 8, seed=3))
    p = load_pddl(str(PDDL / "logistics" / "domain.pddl"), str(prob))
    task = build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: a.cost(p.init))
    py, c = both(mode, task)
    assert py == c and py[0] is PlanStatus.SOLVED and py[2] > 50
    py, c = both(mode, task, method="lama")
    assert py == c and py[0] is PlanStatus.SOLVED and py[2] > 50
    same_evaluations(mode, task, walk_states(task, 30, seed=1))


@needs_kernel
@pytest.mark.parametrize("method", ["gbfs", "lama"])
@pytest.mark.parametrize("stop_after", [0, 1, 7])
def test_node_and_time_limits_stop_at_the_same_expansion(mode: Callable[[str], None], stop_after: int,
                                                         method: str) -> None:
    task = pddl_task("logistics", "p04.pddl")
    py, c = both(mode, task, method=method, max_nodes=stop_after)
    assert py == c and py[0] is PlanStatus.NODE_LIMIT and py[2] == stop_after + 1
    results = []
    for m in ("python", "c"):
        calls = [0]

        def out_of_time() -> bool:
            calls[0] += 1
            return calls[0] > stop_after

        mode(m)
        results.append((summary(forward.search(task, method=method, out_of_time=out_of_time), task), calls[0]))
    assert results[0] == results[1] and results[0][0][0] is PlanStatus.TIME_LIMIT


@needs_kernel
@pytest.mark.parametrize("method", ["gbfs", "lama"])
def test_an_error_in_the_time_callback_propagates(mode: Callable[[str], None], method: str) -> None:
    def boom() -> bool:
        raise RuntimeError("clock broke")

    mode("c")
    with pytest.raises(RuntimeError, match="clock broke"):
        forward.search(pddl_task("gripper", "p02.pddl"), method=method, out_of_time=boom)


@needs_kernel
def test_the_kernel_refuses_bad_input() -> None:
    assert _cls is not None
    k = _cls(2, [(0,)], [(1,)], [()], [1.0], [1], [[0], []], [], "ff")
    assert k.evaluate(frozenset({0})) == (1.0, [0]) and k.evaluations == 1
    assert k.applicable([0, 0]) == [0] and k.applicable([1]) == []
    with pytest.raises(IndexError):
        k.evaluate({2})
    with pytest.raises(IndexError):
        k.applicable({-1})
    with pytest.raises(ValueError):
        _cls(2, [(0,)], [], [()], [1.0], [1], [[0], []], [], "ff")
    with pytest.raises(ValueError):
        _cls(2, [(0,)], [(1,)], [()], [1.0], [1], [[0], []], [], "hmax")
    with pytest.raises(IndexError):
        _cls(2, [(5,)], [(1,)], [()], [1.0], [1], [[0], []], [], "ff")
    # LAMA: landmark {1} (the goal) reached by action 0; bad landmark lists are refused
    from nowplan.planning import _kernel

    status, plan, *_ = k.lama([0], 10, [[1]], [[]])
    assert status == _kernel.SOLVED and plan == [0]
    assert k.lama([0], 10, [[1], [0, 1]], [[], [0]])[:2] == (_kernel.SOLVED, [0])
    assert k.lama([0], 10, [[1]], [[]], None, 1000, True)[0] == _kernel.DEAD_INIT  # a landmark is unreachable
    with pytest.raises(IndexError):
        k.lama([0], 10, [[7]], [[]])
    with pytest.raises(ValueError):
        k.lama([0], 10, [[]], [[]])
    with pytest.raises(ValueError):
        k.lama([0], 10, [[1]], [[], []])
    with pytest.raises(IndexError):
        k.lama([0], 10, [[1]], [[3]])


def same_improvement(mode: Callable[[str], None], task: Task, bound: float, weights: tuple[float, ...],
                     limit: int) -> list[list[int] | None]:
    """The bounded weighted A* of the anytime improvement on both paths (stopped after ``limit`` calls)."""
    found = []
    for w in weights:
        out = []
        for m in ("python", "c"):
            mode(m)
            h = RelaxedHeuristic(task)
            calls = [0]

            def stop() -> bool:
                calls[0] += 1
                return calls[0] > limit

            if m == "python":
                res = anytime._bounded_wastar(task, h, forward._Successors(task), w, bound, stop)
            else:
                assert h.native is not None
                res = h.native.bounded_wastar(task.init, task.cost, w, bound, stop)
            out.append((res, calls[0]))
        assert out[0] == out[1], w
        found.append(out[0][0])
    return found


@needs_kernel
@pytest.mark.parametrize(("domain", "problem"), PROBLEMS)
def test_pddl_improvement_searches_are_identical(mode: Callable[[str], None], domain: str, problem: str) -> None:
    task = pddl_task(domain, problem)
    mode("c")
    res = forward.search(task)
    assert res.actions is not None
    plan = [task.actions.index(a) for a in res.actions]
    bound = sum(task.cost[a] for a in plan)
    for found in same_improvement(mode, task, bound, anytime.WEIGHTS, 400):
        assert found is None or sum(task.cost[a] for a in found) < bound
    # with no bound to beat, the first plan found is returned
    assert all(f is not None for f in same_improvement(mode, task, math.inf, (5.0,), 10**6))


@needs_kernel
@pytest.mark.parametrize("stop_after", [0, 3])
def test_improvement_stops_at_the_same_call(mode: Callable[[str], None], stop_after: int) -> None:
    task = pddl_task("logistics", "p04.pddl")
    assert same_improvement(mode, task, math.inf, (1.0,), stop_after) == [None]


# --------------------------------------------------------------------------- random integer tasks


@needs_kernel
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(task=int_tasks(), seed=st.integers(0, 1000))
def test_random_tasks_evaluate_identically(mode: Callable[[str], None], task: Task, seed: int) -> None:
    same_evaluations(mode, task, walk_states(task, 8, seed))


@needs_kernel
@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(task=int_tasks(), kind=st.sampled_from(KINDS), cost_type=st.sampled_from(COST_TYPES),
       method=st.sampled_from(["gbfs", "astar", "lama"]))
def test_random_tasks_search_identically(mode: Callable[[str], None], task: Task, kind: str, cost_type: str,
                                         method: str) -> None:
    py, c = both(mode, task, method=method, heuristic=kind, cost_type=cost_type, max_nodes=200)
    assert py == c


@needs_kernel
@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(task=int_tasks(), weight=st.sampled_from([1.0, 2.0, 5.0]), bound=st.sampled_from([2.0, 4.5, 9.0, math.inf]))
def test_random_tasks_improve_identically(mode: Callable[[str], None], task: Task, weight: float,
                                          bound: float) -> None:
    same_improvement(mode, task, bound, (weight,), 200)


@needs_kernel
def test_costs_beyond_the_buckets_use_the_heap_in_order(mode: Callable[[str], None]) -> None:
    # two routes to the goal fact 3, one via bucket costs and one via a cost above the bucket range
    task = int_task(5, [([0], [1], [], 2.0**21), ([0], [2], [], 1.0), ([2], [4], [], 2.0**21 - 1.0),
                        ([1], [3], [], 0.0), ([4], [3], [], 0.0), ([0], [3], [], 2.0**22)], [0], [3])
    same_evaluations(mode, task, [task.init, frozenset({0, 2}), frozenset({1}), frozenset({4})])


# --------------------------------------------------------------------------- switching


def test_pure_python_is_forced_by_the_environment(mode: Callable[[str], None],
                                                  caplog: pytest.LogCaptureFixture) -> None:
    task = pddl_task("gripper", "p01.pddl")
    mode("python")
    with caplog.at_level(logging.DEBUG, logger="nowplan.planning.native"):
        native._logged.clear()
        assert RelaxedHeuristic(task).native is None
        res = forward.search(task)
    assert res.status is PlanStatus.SOLVED
    assert sum(native.ENV in r.getMessage() for r in caplog.records) == 1  # logged once
    mode("c")
    assert (RelaxedHeuristic(task).native is None) == (_cls is None)


@pytest.mark.parametrize("broken", ["missing", "stale"])
def test_without_the_compiled_kernel_the_python_code_runs(mode: Callable[[str], None],
                                                          monkeypatch: pytest.MonkeyPatch, broken: str) -> None:
    task = pddl_task("logistics", "p02.pddl")
    mode("python")
    expected = summary(forward.search(task), task)
    if broken == "missing":
        monkeypatch.setitem(sys.modules, "nowplan.planning._kernel", None)  # import raises ImportError
    else:
        monkeypatch.setattr(native, "API", -1)
    monkeypatch.setattr(native, "_loaded", None)
    mode("c")
    assert native.kernel_class() is None and RelaxedHeuristic(task).native is None
    assert summary(forward.search(task), task) == expected
    assert expected[0] is PlanStatus.SOLVED


def naive_landmark_sets(task: Task) -> list[frozenset[int] | None]:
    """Zhu and Givan's fixpoint by plain rounds over all actions, until nothing changes."""
    lm: list[frozenset[int] | None] = [None] * len(task.facts)
    for f in task.init:
        lm[f] = frozenset((f,))
    changed = True
    while changed:
        changed = False
        for a, pre in enumerate(task.pre):
            sets = [lm[p] for p in pre]
            if any(s is None for s in sets):
                continue
            union = frozenset().union(*cast(list[frozenset[int]], sets))
            for e in task.add[a]:
                if e in task.init:
                    continue
                old = lm[e]
                new = union | {e} if old is None else old & (union | {e})
                if new != old:
                    lm[e], changed = new, True
    return lm


@settings(max_examples=300, deadline=None)
@given(task=int_tasks())
def test_landmark_sets_are_the_fixpoint(task: Task) -> None:
    from nowplan.planning.landmarks import landmark_sets

    assert landmark_sets(task) == naive_landmark_sets(task)
