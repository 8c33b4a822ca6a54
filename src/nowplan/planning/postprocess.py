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
the goal.  The result is the same as replaying every try from the initial
state; on a 199-step logistics plan (benchmarks/classical.py --scale) the
whole pass fell from 0.20 s to a few hundredths under cProfile.
"""

from __future__ import annotations

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


def eliminate_actions(task: Task, plan: list[int]) -> list[int]:
    """The plan with unneeded actions removed (greedy action elimination)."""
    cost = task.cost
    ev = evaluator(task)
    states = _states(task, ev, plan)
    i = 0
    while i < len(plan):
        shorter = _run(task, plan, i, states)
        if shorter is not None and (sum(cost[a] for a in shorter) < sum(cost[a] for a in plan) or
                                    len(shorter) < len(plan) and
                                    sum(cost[a] for a in shorter) <= sum(cost[a] for a in plan)):
            plan = shorter  # re-examine from the same position
            states = _states(task, ev, plan)
        else:
            i += 1
    return plan
