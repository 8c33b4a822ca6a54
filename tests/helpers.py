"""Shared helpers for the tests: replaying plans in a symbolic state, process states, example domains."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.core.domain import Domain
from nowplan.domains import registry
from nowplan.domains.registry import DomainSpec
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


EXAMPLES = Path(__file__).resolve().parents[1] / "examples"


def example_spec(monkeypatch: pytest.MonkeyPatch, name: str) -> DomainSpec:
    """The example domain ``examples/NAME`` (package ``NAME_domain``) found as a user's plugin is: on the
    path and named in ``NOWPLAN_DOMAINS``, with a fresh discovery (the registry restored afterwards)."""
    monkeypatch.syspath_prepend(str(EXAMPLES / name))
    monkeypatch.setattr(registry, "_REGISTRY", {})
    monkeypatch.setattr(registry, "_DISCOVERED", False)
    monkeypatch.setenv("NOWPLAN_DOMAINS", f"{name}_domain")
    return registry.get_domain(name)
