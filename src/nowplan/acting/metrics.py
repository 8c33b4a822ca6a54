"""Run outcomes and the metrics summary every run ends with."""

from __future__ import annotations

import enum
from collections import Counter
from dataclasses import dataclass, field
from typing import Any


class Outcome(enum.Enum):
    """How a run ended."""

    REACHED = "reached"  # the goal holds in the world's state (in the belief when the world cannot tell)
    FAILED = "failed"  # a strategy gave up (the reason says why)
    LIMIT = "limit"  # an action, replan or time budget ran out
    LIVELOCK = "livelock"  # the agent's own actions kept bringing it back (nowplan.acting.progress)


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
    plans_rejected: int = 0  # of plan_failures: plans made but set aside (aggressive, a refinement's floors)
    wall_s: float = 0.0
    # judged in the world (see nowplan.worlds.base.Inspectable): does the goal hold in the world's
    # true state (None: the world cannot tell), and the goal's atoms on which belief and world disagree
    goal_in_world: bool | None = None
    goal_in_belief: bool | None = None
    disagreement: tuple[str, ...] = ()
    cycles: int = 0  # cycles detected by the progress guard
    failed_actions: int = 0  # actions the world reported failed
    exogenous_changes: int = 0  # observations that reported a change the world made by itself
    flat_fallbacks: int = 0  # root goals planned concretely as a last resort (acting/refine_flat.py)

    def world_summary(self) -> str:
        """What the world did meanwhile, for a reason that a budget ended a run."""
        return (f"{self.failed_actions} of {self.actions} actions failed, {self.exogenous_changes} exogenous "
                f"change(s), {self.cycles} cycle(s) detected")

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
            "plans_rejected": self.plans_rejected,
            "wall_s": round(self.wall_s, 6),
            "goal_in_world": self.goal_in_world,
            "goal_in_belief": self.goal_in_belief,
            "disagreement": list(self.disagreement),
            "cycles": self.cycles,
            "failed_actions": self.failed_actions,
            "exogenous_changes": self.exogenous_changes,
            "flat_fallbacks": self.flat_fallbacks,
        }

    def summary(self) -> str:
        counts = ", ".join(f"{k}={v}" for k, v in sorted(self.action_counts.items()))
        return (
            f"outcome: {self.outcome.value}{' (' + self.reason + ')' if self.reason else ''}\n"
            f"actions: {self.actions} [{counts}]\n"
            f"execution cost: {self.execution_cost:g}\n"
            f"plans made: {self.plans_made}, replans: {self.replans}, "
            f"planner failures: {self.plan_failures}"
            + (f" ({self.plans_rejected} of them plans made but set aside)" if self.plans_rejected else "")
            + "\n"
            f"planning CPU time: {self.planning_cpu_s:.3f} s; wall time of the whole run: {self.wall_s:.3f} s "
            "(planning, acting, the simulated world, and drawing frames if any)"
            + (f"\nbelief and world disagree on: {', '.join(self.disagreement)}" if self.disagreement else "")
            + (f"\ncycles detected: {self.cycles}" if self.cycles else "")
            + (f"\nlast resort: {self.flat_fallbacks} root goal(s) planned concretely, the hierarchy's "
               "abstract plans making no progress (the switch nofallback gives up instead)"
               if self.flat_fallbacks else "")
        )
