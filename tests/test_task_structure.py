"""The forward task's state-free structure, kept across calls (planning/task.py).

A task built from a kept structure (later calls on one problem, other level
overrides, other states, other goals) must equal one built from scratch: the
same actions with the same precondition, add and delete facts, the same
initial state and goal.  Costs are kept only when every cost is state-free.
"""

from __future__ import annotations

from pathlib import Path

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action, StateFreeCost
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import task_grounding
from nowplan.planning.task import Task, build_task

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"


def _rows(t: Task) -> dict[tuple[str, tuple[object, ...]], tuple[frozenset[Atom], frozenset[Atom], frozenset[Atom]]]:
    """Each action's rows as atoms (ids may differ between two tasks)."""
    out = {}
    for k, act in enumerate(t.actions):
        out[act.key] = (frozenset(t.facts[f] for f in t.pre[k]), frozenset(t.facts[f] for f in t.add[k]),
                        frozenset(t.facts[f] for f in t.dele[k]))
    return out


def _state(t: Task, s: frozenset[int]) -> frozenset[Atom]:
    return frozenset(t.facts[f] for f in s)


def _fresh(*args: object) -> Task:
    task_grounding._CACHE.clear()
    return build_task(*args)  # type: ignore[arg-type]


def _all_operators(p: Problem, level: int) -> None:
    """Ground every operator first: the calls that follow share that grounding whatever their goal's
    relevant operators (planning/relevance.py), so only the structure's reuse is under test."""
    task_grounding.grounding(p.domain, p.objects, p.init, level)


def _logistics_top() -> tuple[Problem, int, Task]:
    """Logistics p02 with its criticalities, every top-level operator grounded, and the task at the top level."""
    p = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p02.pddl",
                  DATA / "logistics" / "logistics.crit")
    top = p.domain.top_level
    task_grounding._CACHE.clear()
    _all_operators(p, top)
    return p, top, build_task(p.domain, p.objects, p.init, p.goal, LevelMap(top), lambda a: 1.0)


def test_a_kept_structure_gives_the_task_a_fresh_build_gives() -> None:
    p, top, first = _logistics_top()
    # a level map that moves two actions down: only their rows change
    moved = [a for a in first.actions if not a.is_primitive(top)][:2]
    assert moved, "the test needs abstract actions at the top level"
    levels = LevelMap(top, frozenset((a.key, -1) for a in moved))
    goal = Goal.of(list(p.goal.atoms)[:1])
    kept = build_task(p.domain, p.objects, p.init, goal, levels, lambda a: 1.0)
    assert kept.facts is first.facts  # the structure was shared
    task_grounding._CACHE.clear()
    _all_operators(p, top)
    fresh = build_task(p.domain, p.objects, p.init, goal, levels, lambda a: 1.0)
    assert _rows(kept) == _rows(fresh)
    assert _state(kept, kept.init) == _state(fresh, fresh.init)
    assert _state(kept, frozenset(kept.goal)) == _state(fresh, frozenset(fresh.goal))
    # the moved actions' rows are those of their lower level, the others those of the top level
    rows_top = _rows(first)
    for a in moved:
        assert _rows(kept)[a.key][0] >= rows_top[a.key][0]
        assert _rows(kept)[a.key] != rows_top[a.key] or a.is_primitive(-1) == a.is_primitive(top)
    # the shared structure's own rows were not changed by the override
    assert _rows(build_task(p.domain, p.objects, p.init, p.goal, LevelMap(top), lambda a: 1.0)) == rows_top
    # the successor index follows the moved rows
    for k in range(len(kept.actions)):
        for f in kept.pre[k]:
            assert k in kept.by_pre[f]
    assert sorted(kept.no_pre) == [k for k in range(len(kept.actions)) if not kept.pre[k]]
    # the adders index (landmarks read it) follows the moved rows too
    adders: dict[int, list[int]] = {}
    for k, row in enumerate(kept.add):
        for f in row:
            adders.setdefault(f, []).append(k)
    assert kept.memo["adders"] == adders


def test_a_negative_goal_gives_the_fresh_task() -> None:
    p = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl")
    lv = flat_levels()
    build_task(p.domain, p.objects, p.init, p.goal, lv, lambda a: 1.0)
    goal = Goal.of([next(iter(p.goal.atoms)).negate()])  # a negative goal: its "not" fact is new
    kept = build_task(p.domain, p.objects, p.init, goal, lv, lambda a: 1.0)
    fresh = _fresh(p.domain, p.objects, p.init, goal, lv, lambda a: 1.0)
    assert _rows(kept) == _rows(fresh)
    assert _state(kept, kept.init) == _state(fresh, fresh.init)
    assert _state(kept, frozenset(kept.goal)) == _state(fresh, frozenset(fresh.goal))


class _Flat(StateFreeCost):
    def __call__(self, bindings: object, belief: object = None) -> float:
        return 3.0


def test_costs_are_kept_only_when_asked_and_state_free() -> None:
    p = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl")
    lv = flat_levels()
    calls: list[Action] = []

    def cost_of(a: Action) -> float:
        calls.append(a)
        return 1.0

    build_task(p.domain, p.objects, p.init, p.goal, lv, cost_of, cache_costs=True)
    n = len(calls)
    assert n > 0
    build_task(p.domain, p.objects, p.init, p.goal, lv, cost_of, cache_costs=True)
    assert len(calls) == n  # kept: gripper's costs are numbers
    t = build_task(p.domain, p.objects, p.init, p.goal, lv, lambda a: 2.0)
    assert set(t.cost) == {2.0}  # without cache_costs the caller's costs count
    assert all(a.cost_is_state_free for a in t.actions)
    assert _Flat()({}, None) == 3.0


def test_a_belief_reading_cost_is_not_state_free() -> None:
    from dataclasses import replace

    p = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl")
    op = replace(p.domain.operators[0], cost=lambda b, belief: 1.0)
    assert not Action(op, tuple("x" for _ in op.params)).cost_is_state_free
    op2 = replace(p.domain.operators[0], cost=_Flat())
    assert Action(op2, tuple("x" for _ in op2.params)).cost_is_state_free


def test_a_floored_map_moves_the_rows_of_the_floored_operator_only() -> None:
    # a floor (acting/refine.py's swaps) lowers every instance of an operator: the structure of the map
    # without it is kept and those rows are made anew, as if each instance were overridden to its level
    p, top, plain = _logistics_top()
    name = next(a.name for a in plain.actions if not a.is_primitive(top))
    floored = LevelMap(top, floors=frozenset({(name, -1)}))
    kept = build_task(p.domain, p.objects, p.init, p.goal, floored, lambda a: 1.0)
    assert kept.facts is plain.facts  # one structure for both maps
    # the floored rows are kept beside it: a second call under the floor moves no row again
    assert build_task(p.domain, p.objects, p.init, p.goal, floored, lambda a: 1.0).pre is kept.pre
    as_overrides = LevelMap(top, frozenset((a.key, -1) for a in plain.actions if a.name == name))
    other = build_task(p.domain, p.objects, p.init, p.goal, as_overrides, lambda a: 1.0)
    assert _rows(kept) == _rows(other)
    rows_top = _rows(plain)
    changed = {k for k, r in _rows(kept).items() if r != rows_top[k]}
    assert changed and all(k[0] == name for k in changed)
    for k in range(len(kept.actions)):
        for f in kept.pre[k]:
            assert k in kept.by_pre[f]
    assert sorted(kept.no_pre) == [k for k in range(len(kept.actions)) if not kept.pre[k]]
    assert all(sorted(v) == v for v in kept.by_pre.values())
    adders: dict[int, list[int]] = {}
    for k, row in enumerate(kept.add):
        for f in row:
            adders.setdefault(f, []).append(k)
    assert kept.memo["adders"] == adders



def _walk_matches_full_exclusions(p: Problem, seed: int) -> int:
    """An abstract level's rows leave out the exclusions a kept precondition implies; along a random
    walk from the initial state their successors are the ones with every exclusion deleted.  Returns
    how many steps deleted an atom only an exclusion deletes (the walk tested that case)."""
    import random

    from nowplan.belief.symbolic import SymbolicBelief
    from nowplan.planning.fact_mutex import Excluder

    top = p.domain.top_level
    assert top > 0 and p.domain.rules.conflicts
    belief = SymbolicBelief(p.init)
    task = build_task(p.domain, p.objects, belief, p.goal, LevelMap(top), lambda a: 1.0)
    gr = task_grounding.grounding(p.domain, p.objects, belief, top)
    excluder = Excluder(p.domain, gr.reached)
    rng = random.Random(seed)
    state = task.init
    atoms = {a for a in p.init.atoms() if a.value is True and a in task.index}
    excluded = 0
    for _ in range(40):
        ok = [k for k in range(len(task.actions)) if all(f in state for f in task.pre[k])]
        if not ok:
            break
        k = rng.choice(ok)
        act = task.actions[k]
        adds = {e for e in act.effects() if e.value is True}
        plain = {e.negate() for e in act.effects() if e.value is False}
        dels = (plain | excluder(adds)) - adds
        excluded += bool((atoms & dels) - plain)
        atoms = (atoms - dels) | {a for a in adds if a in task.index}
        state = state.difference(task.dele[k]).union(task.add[k])
        assert {task.facts[f] for f in state if task.facts[f].value is True} == atoms, act.pddl()
    return excluded


CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"


def test_abstract_rows_drop_only_exclusions_a_kept_precondition_implies(tmp_path: Path) -> None:
    from nowplan.planning.problem_hierarchy import prepare_problem

    for name in ("gripper", "zenotravel", "logistics", "driverlog", "depots"):
        p = prepare_problem(load_pddl(CLASSICAL / name / "domain.pddl", CLASSICAL / name / "p02.pddl", "auto"))
        for seed in range(3):
            _walk_matches_full_exclusions(p, seed)
    # a hand-written level that hides where the robot is: an abstract move leaves it in two rooms
    # unless the exclusion deletes the one it was in (no kept precondition implies that one)
    (tmp_path / "d.pddl").write_text("""(define (domain rooms) (:requirements :strips :typing) (:types room)
  (:predicates (at-robby ?r - room) (visited ?r - room) (charged))
  (:action charge :parameters () :precondition (and) :effect (charged))
  (:action move :parameters (?from ?to - room) :precondition (and (at-robby ?from) (charged))
    :effect (and (at-robby ?to) (not (at-robby ?from)) (visited ?to))))""")
    (tmp_path / "p.pddl").write_text("""(define (problem r3) (:domain rooms) (:objects a b c d - room)
  (:init (at-robby a)) (:goal (and (visited b) (visited c) (visited d))))""")
    (tmp_path / "rooms.crit").write_text("default 2\nmove at-robby 1\n")
    p = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl", tmp_path / "rooms.crit")
    assert sum(_walk_matches_full_exclusions(p, seed) for seed in range(3)) > 0
