"""What the drone believes: a position estimate with its spread, the battery, the parcels."""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from typing import Any

from nowplan.api import Action, Atom, Goal, Observation

Pose = tuple[float, float]
GUST_SIGMA = 0.02  # the spread a step adds, for gusts the drone cannot see


def dist(a: Pose, b: Pose) -> float:
    return math.hypot(a[0] - b[0], a[1] - b[1])


@dataclass(frozen=True)
class Telemetry:
    """What the drone reads after an action: battery, what it carries, what the depot has received,
    and a position fix (only after a ``localize`` that succeeded)."""

    battery: float
    held: str | None
    delivered: frozenset[str]
    parcels: tuple[tuple[str, Pose], ...]  # where undelivered parcels on the ground lie (the dispatcher's list)
    fix: Pose | None = None


@dataclass
class DroneBelief:
    """A Gaussian position estimate (mean, isotropic sigma) and what telemetry reports."""

    pos: Pose
    sigma: float
    battery: float
    parcels: dict[str, Pose]
    held: str | None = None
    delivered: set[str] = field(default_factory=set)
    drift: float = 0.05  # position spread added per unit flown
    fix_sigma: float = 0.05  # the position sensor's noise

    def update(self, action: Action, observation: Observation) -> None:
        t = observation.data
        if action.name == "fly" and observation.success:
            args: Any = action.args
            to: Pose = args[1]
            self.sigma = math.hypot(self.sigma, self.drift * dist(self.pos, to))
            self.pos = to
        elif action.name in ("pick", "drop", "charge") and not observation.success:
            self.sigma = max(self.sigma, 0.5)  # a failure there says we may not be where we think
        elif action.name == "fly" and observation.info.get("reason") == "battery too low for the flight":
            self.sigma = max(self.sigma, 1.0)  # the leg is longer than we think: we are not where we think
        self.sigma = math.hypot(self.sigma, GUST_SIGMA)
        if not isinstance(t, Telemetry):
            return
        if t.fix is not None:  # a Kalman update of the mean and spread
            k = self.sigma ** 2 / (self.sigma ** 2 + self.fix_sigma ** 2)
            self.pos = (self.pos[0] + k * (t.fix[0] - self.pos[0]), self.pos[1] + k * (t.fix[1] - self.pos[1]))
            self.sigma = math.sqrt((1 - k)) * self.sigma
        self.battery, self.held, self.delivered = t.battery, t.held, set(t.delivered)
        self.parcels = dict(t.parcels)

    def fingerprint(self) -> Hashable:
        """The situation, for the progress guard (to a centimetre and a percent)."""
        return (round(self.pos[0], 2), round(self.pos[1], 2), round(self.sigma, 2), round(self.battery, 2),
                self.held, tuple(sorted(self.delivered)), tuple(sorted(self.parcels.items())))

    @property
    def planning_heuristic(self) -> Callable[[Goal, Any, Callable[[Atom], bool]], float]:
        """An estimate of what the subgoal still costs from here (the planner's tests can only count
        unmet atoms): the longest way the drone must fly for it, plus a step per other unmet atom."""
        return drone_estimate

    def snapshot(self) -> dict[str, Any]:
        return {"pos": self.pos, "sigma": self.sigma, "battery": self.battery, "held": self.held}


def drone_estimate(goal: Goal, belief: Any, holds: Callable[[Atom], bool]) -> float:
    """How far the drone must fly for ``goal`` (the farthest pose it names) plus a step per unmet atom."""
    from drone_domain.model import DEPOT  # noqa: PLC0415 (the model imports this module)

    far, steps = 0.0, 0.0
    for a in goal.atoms:
        if holds(a):
            continue
        steps += 1.0
        if a.predicate == "At" and a.value is True:
            pose: Any = a.args[0]
            far = max(far, dist(belief.pos, pose))
        elif a.predicate in ("Holding", "Delivered") and a.value is True:
            where = belief.parcels.get(a.args[0])
            if where is not None:
                far = max(far, dist(belief.pos, where) + (dist(where, DEPOT) if a.predicate == "Delivered" else 0.0))
    return far + steps
