"""Run outcomes and the metrics summary every run ends with."""

from __future__ import annotations

import enum
from collections import Counter
from dataclasses import dataclass, field
from typing import Any


class Outcome(enum.Enum):
    """How a run ended."""

    REACHED = "reached"  # the goal holds in the agent's belief (and the world's state)
    FAILED = "failed"  # a strategy gave up (the reason says why)
    LIMIT = "limit"  # an action, replan or time budget ran out


@dataclass
class Metrics:
    """What one run measured: its outcome and reason, actions, costs, plans, replans and times."""

    outcome: Outcome = Outcome.FAILED
    reason: str = ""
    actions: int = 0
    action_counts: Counter[str] = field(default_factory=Counter)
    execution_cost: float = 0.0
    planning_cpu_s: float = 0.0
    plans_made: int = 0
    replans: int = 0
    plan_failures: int = 0
    wall_s: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return {
            "outcome": self.outcome.value,
            "reason": self.reason,
            "actions": self.actions,
            "action_counts": dict(sorted(self.action_counts.items())),
            "execution_cost": round(self.execution_cost, 6),
            "planning_cpu_s": round(self.planning_cpu_s, 6),
            "plans_made": self.plans_made,
            "replans": self.replans,
            "plan_failures": self.plan_failures,
            "wall_s": round(self.wall_s, 6),
        }

    def summary(self) -> str:
        counts = ", ".join(f"{k}={v}" for k, v in sorted(self.action_counts.items()))
        return (
            f"outcome: {self.outcome.value}{' (' + self.reason + ')' if self.reason else ''}\n"
            f"actions: {self.actions} [{counts}]\n"
            f"execution cost: {self.execution_cost:g}\n"
            f"plans made: {self.plans_made}, replans: {self.replans}, "
            f"planner failures: {self.plan_failures}\n"
            f"planning CPU time: {self.planning_cpu_s:.3f} s; wall time of the whole run: {self.wall_s:.3f} s "
            "(planning, acting, the simulated world, and drawing frames if any)"
        )
