"""Plan post-processing: greedy action elimination (Fink and Yang; Nakhost and Müller).

A satisficing search's plan often carries actions that nothing needs (a
gripper picking up and putting down, a detour).  For each action in turn,
remove it together with every later action that becomes inapplicable
without it; keep the shorter plan if it still reaches the goal and costs
less.  Never makes a plan worse.

Each try replays only the suffix after the removed step: the states the
current plan passes through are kept (the prefix before the step is
unchanged), and a replay whose state meets the current plan's state again
at the same step stops there, since the rest applies as before and reaches
the goal.  Without axioms, states are bit masks over fact ids (Python
ints: an action applies when ``state & pre == pre``).  The result is the
same as replaying every try from the initial state (a hypothesis test checks
it); on logistics scale s05 (~190-step plans, 967 tries over the first plan
and the anytime improvement's) the passes fell from 0.59 s to 0.11 s under
cProfile.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TypeVar

from nowplan.planning.axioms import AxiomEvaluator, evaluator
from nowplan.planning.task import Task


def _step(task: Task, ev: AxiomEvaluator | None, state: set[int], a: int) -> set[int]:
    state.difference_update(task.dele[a])
    state.update(task.add[a])
    return set(ev.evaluate(state)) if ev is not None else state


def _states(task: Task, ev: AxiomEvaluator | None, plan: list[int]) -> list[frozenset[int]] | None:
    """The state before each step and after the last (``len(plan) + 1``), or None if a step does not
    apply or the goal fails (then every try replays from the start)."""
    state = set(task.init)
    out = [frozenset(state)]
    for a in plan:
        if not all(p in state for p in task.pre[a]):
            return None
        state = _step(task, ev, state, a)
        out.append(frozenset(state))
    return out if all(g in state for g in task.goal) else None


def _run(task: Task, plan: list[int], skip: int, states: list[frozenset[int]] | None = None) -> list[int] | None:
    """``plan`` without step ``skip`` and the later steps left inapplicable; ``None`` if the goal fails.

    ``states``: :func:`_states` of ``plan`` (the replay starts at step ``skip`` and stops where it
    meets the plan's own state again)."""
    ev = evaluator(task)
    start = skip if states is not None else 0
    state = set(states[skip]) if states is not None else set(task.init)
    kept: list[int] = list(plan[:start])
    for i in range(start, len(plan)):
        if states is not None and i > skip and state == states[i]:
            return kept + plan[i:]  # back on the plan's own trajectory: the rest applies as before
        a = plan[i]
        if i == skip or not all(p in state for p in task.pre[a]):
            continue
        state = _step(task, ev, state, a)
        kept.append(a)
    return kept if all(g in state for g in task.goal) else None


def _mask(facts: Iterable[int]) -> int:
    bits = bytearray((max(facts, default=-1) >> 3) + 1)  # one pass: ``m |= 1 << f`` per fact is quadratic
    for f in facts:
        bits[f >> 3] |= 1 << (f & 7)
    return int.from_bytes(bits, "little")


def _masks(task: Task, plan: Iterable[int]) -> dict[int, tuple[int, int, int]]:
    """Preconditions, adds and kept facts (the complement of the deletes, as a negative int) of the plan's
    actions as bit masks over fact ids, made when an action is first met and kept with the task.  Only the
    plan's actions: a pass replays sub-sequences of its plan, and a task of a hierarchical run's call has
    tens of thousands of actions of which its plan uses a handful (satellite-50: masks of every action
    made per call were half of auto-HPN's run)."""
    hit: dict[int, tuple[int, int, int]] | None = task.memo.get("bitmasks")
    if hit is None:
        hit = task.memo["bitmasks"] = {}
    for a in plan:
        if a not in hit:
            hit[a] = (_mask(task.pre[a]), _mask(task.add[a]), ~_mask(task.dele[a]))
    return hit


def _run_bits(task: Task, plan: list[int], skip: int, states: list[int], goal: int) -> list[int] | None:
    """:func:`_run` over bit-mask states (a task without axioms): the same result."""
    masks = _masks(task, ())  # made by _states_bits for every action of the plan
    state = states[skip]
    kept = plan[:skip]
    for i in range(skip + 1, len(plan)):
        if state == states[i]:
            return kept + plan[i:]
        a = plan[i]
        p, add, keep = masks[a]
        if state & p == p:
            state = state & keep | add
            kept.append(a)
    return kept if state & goal == goal else None


def _states_bits(task: Task, plan: list[int], goal: int) -> list[int] | None:
    masks = _masks(task, plan)
    state = _mask(task.init)
    out = [state]
    for a in plan:
        p, add, keep = masks[a]
        if state & p != p:
            return None
        state = state & keep | add
        out.append(state)
    return out if state & goal == goal else None


def _better(cost: list[float], shorter: list[int], plan: list[int]) -> bool:
    """Whether ``shorter`` costs less than ``plan``, or as much with fewer steps."""
    new, old = sum(cost[a] for a in shorter), sum(cost[a] for a in plan)
    return new < old or (len(shorter) < len(plan) and new <= old)


# steps replayed by one pass at most (~1 s with bit masks): the tries are quadratic in the plan's length, so a
# plan of thousands of steps (visit-all 50x50: 3,218) would spend far longer here than its search did; the
# pass then keeps the plan it has (valid, never costlier).  Plans of a few hundred steps need ~10^5.
MAX_REPLAY_STEPS = 1_000_000


def eliminate_actions(task: Task, plan: list[int]) -> list[int]:
    """The plan with unneeded actions removed (greedy action elimination)."""
    ev = evaluator(task)
    if ev is None:  # states as bit masks: the same tries, several times faster than sets of fact ids
        goal = _mask(task.goal)
        bits = _states_bits(task, plan, goal)
        if bits is not None:
            def states_bits(p: list[int]) -> list[int]:
                again = _states_bits(task, p, goal)
                assert again is not None  # a plan _run_bits returns applies and reaches the goal
                return again

            return _eliminate(task, plan, bits, states_bits, lambda p, i, s: _run_bits(task, p, i, s, goal))
    return _eliminate(task, plan, _states(task, ev, plan), lambda p: _states(task, ev, p),
                      lambda p, i, s: _run(task, p, i, s))


S = TypeVar("S")  # the states a plan passes through, in one representation


def _eliminate(task: Task, plan: list[int], states: S, states_of: Callable[[list[int]], S],
               run: Callable[[list[int], int, S], list[int] | None]) -> list[int]:
    """The elimination loop over one state representation: ``states_of(plan)`` the states the plan passes
    through, ``run(plan, i, states)`` the plan without step ``i`` (and what it leaves inapplicable)."""
    cost = task.cost
    i = 0
    work = 0
    while i < len(plan):  # each try removes an action or moves on: bounded by the plan's length
        work += len(plan) - i
        if work > MAX_REPLAY_STEPS:
            break
        shorter = run(plan, i, states)
        if shorter is not None and _better(cost, shorter, plan):
            plan = shorter  # re-examine from the same position
            states = states_of(plan)
        else:
            i += 1
    return plan
