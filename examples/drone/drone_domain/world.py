"""The true drone: it drifts on every flight, gusts push it, grasps slip, the fix is noisy or missed."""

from __future__ import annotations

import math
from typing import Any

from nowplan.api import Action, SimulatedWorld

from drone_domain.belief import DroneBelief, Pose, Telemetry, dist
from drone_domain.model import DEPOT, RATE, STATIONS

GRAB = 0.35  # the hook reaches a parcel this close
DOCK = 0.4  # a charger or the depot serves the drone this close


class DroneWorld(SimulatedWorld):
    """A continuous world: the drone's true pose and battery, the parcels' true poses."""

    def __init__(self, pos: Pose, battery: float, parcels: dict[str, Pose], *, seed: int = 0,
                 failure_prob: float = 0.0, exogenous_prob: float = 0.0, drift: float = 0.05,
                 fix_sigma: float = 0.05, miss: float = 0.0, slip: float = 0.0) -> None:
        super().__init__(seed=seed, failure_prob=failure_prob, exogenous_prob=exogenous_prob)
        self.pos, self.battery, self.parcels = pos, battery, dict(parcels)
        self.held: str | None = None
        self.delivered: set[str] = set()
        self.drift, self.fix_sigma, self.miss, self.slip = drift, fix_sigma, miss, slip

    def refuse(self, action: Action) -> str | None:
        args: Any = action.args  # (poses and parcel names: the operators' parameters)
        if action.name == "fly":
            if self.battery < RATE * dist(self.pos, args[1]):
                return "battery too low for the flight"
        elif action.name == "pick":
            where = self.parcels.get(args[0])
            if self.held is not None:
                return "the hook is taken"
            if where is None or dist(where, self.pos) > GRAB:
                return "no parcel under the drone"
        elif action.name == "drop":
            if self.held != action.args[0]:
                return f"not carrying {action.args[0]}"
        elif action.name == "charge":
            if min(dist(s, self.pos) for s in STATIONS) > DOCK:
                return "no charger under the drone"
        return None

    def fault(self, action: Action) -> str | None:
        if action.name == "pick" and self.rng.random() < self.slip:
            return "the grasp slipped"
        if action.name == "localize" and self.rng.random() < self.miss:
            # a missed fix is a localize that failed: reported as a success that taught nothing, three
            # in a row looked like a loop to the progress guard (the belief was as it had been)
            return "no position fix"
        return None

    def apply(self, action: Action) -> None:
        args: Any = action.args
        if action.name == "fly":
            to: Pose = args[1]
            d = dist(self.pos, to)
            self.battery = max(0.0, self.battery - RATE * d)
            s = self.drift * d / math.sqrt(2)
            self.pos = (to[0] + self.rng.gauss(0, s), to[1] + self.rng.gauss(0, s))
        elif action.name in ("charge", "call_crew"):
            self.battery = 1.0
        elif action.name == "pick":
            self.held = args[0]
            del self.parcels[args[0]]
        elif action.name == "drop":
            assert self.held is not None
            if dist(self.pos, DEPOT) <= DOCK:
                self.delivered.add(self.held)
            else:  # dropped short of the depot: it lies where it fell, and the dispatcher lists it again
                self.parcels[self.held] = (round(self.pos[0], 2), round(self.pos[1], 2))
            self.held = None

    def exogenous_change(self) -> list[str]:
        """A gust pushes the drone 0.3 units; it does not feel it."""
        a = self.rng.uniform(0, 2 * math.pi)
        self.pos = (self.pos[0] + 0.3 * math.cos(a), self.pos[1] + 0.3 * math.sin(a))
        return ["a gust pushed the drone"]

    def observe(self, action: Action, success: bool) -> Any:
        fix = None
        if action.name == "localize" and success:
            s = self.fix_sigma / math.sqrt(2)
            fix = (self.pos[0] + self.rng.gauss(0, s), self.pos[1] + self.rng.gauss(0, s))
        return Telemetry(round(self.battery, 4), self.held, frozenset(self.delivered),
                         tuple(sorted(self.parcels.items())), fix)

    def true_state(self) -> DroneBelief:
        """The truth, as a belief without doubt: the domain's tests read it (success judged in the world)."""
        return DroneBelief(self.pos, 0.0, self.battery, dict(self.parcels), self.held, set(self.delivered))
