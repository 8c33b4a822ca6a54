"""What generators and the planner may see beyond the goal and the belief."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.planning.plan import Plan


@dataclass(frozen=True)
class PlanningContext:
    """The plan stack (outermost first) for foresight, plus free-form extras.

    Seed 000 replaces line 10 of Fig. 2 so the planner receives the whole
    plan stack: generators can then avoid regions that later subgoals need.
    """

    plan_stack: tuple[Plan, ...] = ()
    extras: Mapping[str, Any] = field(default_factory=dict, hash=False, compare=False)

    def future_requirements(self) -> list[Any]:
        """Every atom still required by a pre-image of the stack's remaining steps."""
        out: list[Any] = []
        for p in self.plan_stack:
            for s in p.steps:
                out.extend(s.goal.atoms)
        return out
