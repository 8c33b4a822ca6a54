"""Action elimination replays only the suffix after the removed step and stops where the replay meets
the plan's own trajectory again; the result must be what a replay of every try from the initial state
gives (the reference below), on plans padded with random applicable detours."""

from __future__ import annotations

import random
from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.core.levels import flat_levels
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import task as task_mod
from nowplan.planning.forward import search
from nowplan.planning.postprocess import eliminate_actions
from nowplan.planning.task import Task

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
_TASKS: dict[str, tuple[Task, list[int]]] = {}


def _task(name: str) -> tuple[Task, list[int]]:
    if name not in _TASKS:
        p = load_pddl(CLASSICAL / name / "domain.pddl", CLASSICAL / name / "p02.pddl")
        t = task_mod.build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: 1.0)
        res = search(t)
        assert res.actions is not None
        ids = {a: i for i, a in enumerate(t.actions)}
        _TASKS[name] = (t, [ids[a] for a in res.actions])
    return _TASKS[name]


def _reference_run(t: Task, plan: list[int], skip: int) -> list[int] | None:
    state = set(t.init)
    kept = []
    for i, a in enumerate(plan):
        if i == skip or not all(p in state for p in t.pre[a]):
            continue
        state.difference_update(t.dele[a])
        state.update(t.add[a])
        kept.append(a)
    return kept if all(g in state for g in t.goal) else None


def _reference(t: Task, plan: list[int]) -> list[int]:
    i = 0
    while i < len(plan):  # each step removes an action or moves on: bounded by the plan's length
        shorter = _reference_run(t, plan, i)
        old, new = sum(t.cost[a] for a in plan), None if shorter is None else sum(t.cost[a] for a in shorter)
        if shorter is not None and new is not None and (new < old or len(shorter) < len(plan) and new <= old):
            plan = shorter
        else:
            i += 1
    return plan


def _padded(t: Task, plan: list[int], rng: random.Random, detours: int) -> list[int]:
    """``plan`` with ``detours`` random applicable actions inserted; cut at the first step that no
    longer applies and completed by nothing (the reference decides what the goal check gives)."""
    out = list(plan)
    for _ in range(detours):
        pos = rng.randrange(len(out) + 1)
        state = set(t.init)
        for a in out[:pos]:
            state.difference_update(t.dele[a])
            state.update(t.add[a])
        app = [a for a in range(len(t.pre)) if all(p in state for p in t.pre[a])]
        if app:
            out.insert(pos, rng.choice(app))
    return out


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(["gripper", "logistics", "blocksworld", "miconic", "depots"]), st.integers(0, 2**16),
       st.integers(0, 6))
def test_suffix_replay_gives_the_same_plan_as_full_replays(name: str, seed: int, detours: int) -> None:
    t, plan = _task(name)
    padded = _padded(t, plan, random.Random(seed), detours)
    assert eliminate_actions(t, padded) == _reference(t, padded)


def test_a_capped_pass_keeps_a_valid_plan_no_costlier(monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """Past MAX_REPLAY_STEPS the pass stops with the plan it has: still valid, never costlier, and with
    no cap reached the same as the reference."""
    from nowplan.planning import postprocess

    t, plan = _task("logistics")

    def valid(p: list[int]) -> bool:
        return _reference_run(t, p, -1) == p  # every step applies (none skipped) and the goal holds

    # the most detours that leave some padding valid (how many depends on the plan the search found)
    padded = next(p for d in (6, 4, 3, 2) for p in (_padded(t, plan, random.Random(s), d) for s in range(200))
                  if valid(p) and p != plan)
    full = eliminate_actions(t, padded)
    monkeypatch.setattr(postprocess, "MAX_REPLAY_STEPS", len(padded) * 2)
    capped = eliminate_actions(t, padded)
    assert valid(capped)
    assert sum(t.cost[a] for a in full) <= sum(t.cost[a] for a in capped) <= sum(t.cost[a] for a in padded)
    assert capped != full  # the cap stopped it early (else this test checks nothing)
