"""Shared helpers for the tests: replaying plans in a symbolic state, process states."""

from __future__ import annotations

from pathlib import Path

from nowplan.core.domain import Domain
from nowplan.core.state import State
from nowplan.planning.plan import Plan


def replay(domain: Domain, state: State, plan: Plan, concrete: bool = True) -> State:
    """Apply the plan step by step, asserting preconditions and every pre-image g_i."""
    assert domain.satisfies(state, plan.preimage(0)), "the start does not satisfy g0"
    for i, step in enumerate(plan.steps[1:], start=1):
        act = step.action
        assert act is not None
        level = None if concrete else plan.levels.level(act)
        for p in act.preconditions(level):
            assert domain.holds(p, state), f"step {i} {act}: precondition {p} false"
        state = state.apply(act.effects())
        assert domain.satisfies(state, plan.preimage(i)), f"g_{i} false after step {i} ({act})"
    assert domain.satisfies(state, plan.goal)
    return state


def process_alive(pid: int) -> bool:
    """Is the process running (Linux /proc; a zombie not yet reaped counts as dead)?"""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return False
    return fields[0] != "Z"
