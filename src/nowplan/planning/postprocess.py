"""Plan post-processing: greedy action elimination (Fink and Yang; Nakhost and Müller).

A satisficing search's plan often carries actions that nothing needs (a
gripper picking up and putting down, a detour).  For each action in turn,
remove it together with every later action that becomes inapplicable
without it; keep the shorter plan if it still reaches the goal and costs
less.  Quadratic in the plan length, and never makes a plan worse.
"""

from __future__ import annotations

from nowplan.planning.axioms import evaluator
from nowplan.planning.task import Task


def _run(task: Task, plan: list[int], skip: int) -> list[int] | None:
    """``plan`` without step ``skip`` and the later steps left inapplicable; ``None`` if the goal fails."""
    ev = evaluator(task)
    state = set(task.init)
    kept: list[int] = []
    for i, a in enumerate(plan):
        if i == skip or not all(p in state for p in task.pre[a]):
            continue
        state.difference_update(task.dele[a])
        state.update(task.add[a])
        if ev is not None:
            state = set(ev.evaluate(state))
        kept.append(a)
    return kept if all(g in state for g in task.goal) else None


def eliminate_actions(task: Task, plan: list[int]) -> list[int]:
    """The plan with unneeded actions removed (greedy action elimination)."""
    cost = task.cost
    i = 0
    while i < len(plan):
        shorter = _run(task, plan, i)
        if shorter is not None and sum(cost[a] for a in shorter) < sum(cost[a] for a in plan):
            plan = shorter  # re-examine from the same position
        elif shorter is not None and len(shorter) < len(plan) and \
                sum(cost[a] for a in shorter) <= sum(cost[a] for a in plan):
            plan = shorter
        else:
            i += 1
    return plan
