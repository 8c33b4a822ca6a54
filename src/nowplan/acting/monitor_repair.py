"""The monitor's three alternatives (seed 003 Fig. 1, ``Replanner()``) and their cost accounting.

After an action, the *expected* world model is the model before it with the
action's effects applied; the *observed* one is the belief after the
observation.  With ``dm`` = distance(expected, observed) and ``dm1`` = the
distance from the observed model to the closest intermediate state of a
stored plan, the seed's rule is:

1. ``dm1 < thr1`` and ``dm1 < dm``: go to that intermediate state and
   continue with its stored plan (:attr:`Alternative.INTERMEDIATE`);
2. else ``0 < dm < thr``: plan back to the expected model, then continue the
   current plan (:attr:`Alternative.RESTORE`);
3. else plan from the observed model to the goal (:attr:`Alternative.GOAL`).

The seed's scheduler also computes each alternative's cost (``alter1-cost()``,
``alter2-cost()`` in Fig. 1) and its text asks the replanner to "make a
decision between backtracking or going directly to a final state" that
minimises cost.  ``rule-cost`` reads it that way: the thresholds decide which
alternatives are *eligible* (1 and 2 as above; replanning to the goal always
is) and the cheapest eligible one by the accounting below is taken.

This module holds the decision rules and the bookkeeping of what each
alternative costs; :mod:`nowplan.acting.monitor` applies them to the plan stack.
"""

from __future__ import annotations

import enum
from collections import Counter
from dataclasses import dataclass, field
from typing import Any

from nowplan.acting.plan_library import StoredPlan
from nowplan.core.atoms import Goal
from nowplan.errors import ScenarioError
from nowplan.planning.plan import Plan


class Alternative(enum.Enum):
    INTERMEDIATE = "intermediate"
    RESTORE = "restore"
    GOAL = "goal"


DECISIONS = ("rule", "goal", "restore", "cost", "rule-cost")


@dataclass(frozen=True)
class MonitorConfig:
    """How the monitor decides and what it counts.

    ``decision``: ``rule`` (the seed's thresholds), ``goal`` (always replan to
    the goal), ``restore`` (always plan back to the expected model, falling
    back to the goal when that is impossible), ``cost`` (plan every
    feasible alternative and take the cheapest by the accounting below) or
    ``rule-cost`` (plan the alternatives the seed's thresholds admit, the
    goal always among them, and take the cheapest).
    ``thr`` bounds ``dm`` for restoring, ``thr_intermediate`` bounds ``dm1``
    (default: ``thr``).  ``restore_target``: ``preimage`` restores only what
    the rest of the current plan needs (its regression pre-image), ``model``
    the whole expected model.  ``library_scope``: ``path`` searches the
    intermediate states of the plan being executed (the seed's "current
    path"), ``goal`` those of every stored plan toward the same goal.
    Cost accounting: an alternative costs its repair plan, plus the stored or
    remaining plan it continues with when ``count_continuation``, plus
    ``planning_weight`` cost units per CPU second spent planning it.
    """

    decision: str = "rule"
    thr: float = 4.0
    thr_intermediate: float | None = None
    restore_target: str = "preimage"
    library_scope: str = "goal"
    library_path: str | None = None  # SQLite file; None keeps the library in memory for one run
    library_write: bool = True  # store this run's plans in the file (False: read it only)
    reuse: bool = True  # reuse a stored plan for an exact (initial, goal) pair instead of planning
    planner: str = "domain"  # domain: the domain's own planner when it registers one | regression
    planning_weight: float = 0.0
    count_continuation: bool = True
    # commit to replanning to the goal when restoring loops (nowplan.acting.monitor_escalation);
    # False: the seed's rule as written (the reproduction of seed 003 measures that)
    escalate: bool = True

    def __post_init__(self) -> None:
        checks: list[tuple[str, Any, tuple[Any, ...]]] = [
            ("decision", self.decision, DECISIONS),
            ("restore_target", self.restore_target, ("preimage", "model")),
            ("library_scope", self.library_scope, ("path", "goal")),
            ("planner", self.planner, ("domain", "regression")),
        ]
        for name, value, ok in checks:
            if value not in ok:
                raise ScenarioError(f"monitor {name} '{value}' is not one of: {', '.join(ok)}")
        if self.thr < 0 or (self.thr_intermediate is not None and self.thr_intermediate < 0):
            raise ScenarioError("monitor thresholds must be >= 0")
        if self.planning_weight < 0:
            raise ScenarioError("monitor planning_weight must be >= 0")

    @property
    def thr1(self) -> float:
        return self.thr if self.thr_intermediate is None else self.thr_intermediate

    @property
    def compares(self) -> bool:
        """Every alternative tried is planned and the cheapest taken (else the first plannable one)."""
        return self.decision in ("cost", "rule-cost")

    @property
    def uses_library(self) -> bool:
        """The decision looks at stored intermediate states (``dm1``)."""
        return self.decision in ("rule", "cost", "rule-cost")


def seed_rule(dm: float, dm1: float | None, thr: float, thr1: float) -> Alternative:
    """The seed's ``Replanner()`` decision, verbatim."""
    if dm1 is not None and dm1 < thr1 and dm1 < dm:
        return Alternative.INTERMEDIATE
    if dm != 0 and dm < thr:
        return Alternative.RESTORE
    return Alternative.GOAL


def order_to_try(config: MonitorConfig, dm: float, dm1: float | None) -> list[Alternative]:
    """The alternatives in the order they are attempted (a later one when an earlier cannot be planned)."""
    if config.decision == "goal":
        return [Alternative.GOAL]
    if config.decision == "restore":
        return [Alternative.RESTORE, Alternative.GOAL]
    if config.decision == "cost":
        out = [Alternative.RESTORE, Alternative.GOAL]
        return ([Alternative.INTERMEDIATE] if dm1 is not None else []) + out
    if config.decision == "rule-cost":
        eligible = []
        if dm1 is not None and dm1 < config.thr1 and dm1 < dm:
            eligible.append(Alternative.INTERMEDIATE)
        if dm != 0 and dm < config.thr:
            eligible.append(Alternative.RESTORE)
        return [*eligible, Alternative.GOAL]
    first = seed_rule(dm, dm1, config.thr, config.thr1)
    out = [first]
    if first is Alternative.INTERMEDIATE and dm != 0 and dm < config.thr:
        out.append(Alternative.RESTORE)
    if first is not Alternative.GOAL:
        out.append(Alternative.GOAL)
    return out


@dataclass(frozen=True)
class Candidate:
    """An intermediate state ``s_index`` of a stored plan, ``distance`` from the observed model."""

    plan: StoredPlan
    index: int
    distance: float


@dataclass(frozen=True)
class Repair:
    """A plan for one alternative and what it is expected to cost.

    ``mode``: ``replace_all`` (pop every plan above the root), ``replace_frame``
    (pop the current plan only) or ``on_top`` (push above the current plan).
    """

    alternative: Alternative
    plan: Plan
    mode: str
    repair_cost: float
    continuation_cost: float
    planning_s: float
    detail: str = ""
    target: Goal | None = None  # the model a restore or intermediate repair goes back to

    def total(self, config: MonitorConfig) -> float:
        cont = self.continuation_cost if config.count_continuation else 0.0
        return self.repair_cost + cont + config.planning_weight * self.planning_s


@dataclass
class MonitorStats:
    surprises: int = 0
    decisions: Counter[str] = field(default_factory=Counter)
    fallbacks: int = 0  # a chosen alternative could not be planned; a later one was used
    unresolved: int = 0  # no alternative could be planned; left to the executive
    reobservations: int = 0  # fresh looks asked of the belief when nothing could be planned
    reuses: int = 0  # plans taken from the library for an exact (initial, goal) pair
    escalated: str = ""  # why the monitor replans to the goal for the rest of the run ("" = it does not)
    hierarchical_goal: str = ""  # why the goal is planned at the strategy's levels ("" = flat)
    loops_dropped: int = 0  # actions cut from composed repairs that returned to a state passed before
    stored: int = 0
    estimated_cost: float = 0.0  # sum of the chosen repairs' accounted costs
    planning_s: float = 0.0  # CPU seconds the monitor spent planning (also in the run's metrics)
    distances: list[float] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {
            "surprises": self.surprises,
            "decisions": dict(sorted(self.decisions.items())),
            "fallbacks": self.fallbacks,
            "unresolved": self.unresolved,
            "reobservations": self.reobservations,
            "reuses": self.reuses,
            "escalated": self.escalated,
            "hierarchical_goal": self.hierarchical_goal,
            "loops_dropped": self.loops_dropped,
            "stored": self.stored,
            "estimated_cost": round(self.estimated_cost, 6),
            "planning_s": round(self.planning_s, 6),
        }
