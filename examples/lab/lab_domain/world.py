"""The simulated lab: a door that sticks, samples that drift, an elevator others call, local sight."""

from __future__ import annotations

import random
from typing import Any

from nowplan.api import Action, Atom, Domain, Observation, State, SymbolicBelief, SymbolicWorld, atom


def floor_of(state: State, spot: object) -> object:
    return next(f for (s, f) in state.facts("on_floor") if s == spot)


def hidden_samples(state: State) -> set[Atom]:
    """The ``at`` facts of samples on a floor other than the robot's: the robot cannot see them."""
    here = floor_of(state, state.facts("robot_at")[0][0])
    tools = {x for (x,) in state.facts("is_tool")}
    return {atom("at", o, s) for (o, s) in state.facts("at") if o not in tools and floor_of(state, s) != here}


def disturb(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: a sample is pushed to a neighbouring spot, someone calls the car, or the door shuts."""
    tools = {x for (x,) in state.facts("is_tool")}
    kind = rng.choice(("drift", "car", "door"))
    if kind == "drift":
        loose = sorted((str(o), str(s)) for (o, s) in state.facts("at") if o not in tools)
        if loose:
            o, s = rng.choice(loose)
            lifts = {x for (x, _) in state.facts("lift")}
            nxt = sorted(str(b) for (a, b) in state.facts("hallway") if a == s and b not in lifts)
            if nxt:
                return [atom("at", o, s, value=False), atom("at", o, rng.choice(nxt))]
    elif kind == "car":
        floors = sorted({str(f) for (_, f) in state.facts("lift")})
        now = str(state.facts("car_at")[0][0])
        to = rng.choice(floors)
        if to != now:
            return [atom("car_at", now, value=False), atom("car_at", to)]
    else:
        doors = sorted(str(a[0]) for a in state.facts("open"))
        if doors:
            return [atom("open", rng.choice(doors), value=False)]
    return []


class LabWorld(SymbolicWorld):
    """The true lab; the robot sees everything on its own floor and the rest of the building's fixtures."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, sticky: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=disturb,
                         exogenous_prob=exogenous_prob)
        self.sticky = sticky

    def fault(self, action: Action) -> str | None:
        if action.name == "open_door" and self.rng.random() < self.sticky:
            return f"door {action.args[0]} is stuck"
        return None

    def observe(self, action: Action, success: bool) -> Any:
        hidden = hidden_samples(self.state)
        return State([a for a in self.state.atoms() if a not in hidden])


class LabBelief(SymbolicBelief):
    """Adopts what it sees; a sample out of sight stays where it was last seen (maybe wrongly)."""

    def update(self, action: Action, observation: Observation) -> None:
        seen = observation.data
        if not isinstance(seen, State):
            super().update(action, observation)
            return
        located = {o for (o, _) in seen.facts("at")} | {o for (o,) in seen.facts("holding")} | {
            o for (o,) in seen.facts("equipped")}
        kept = [atom("at", o, s) for (o, s) in self.state.facts("at") if o not in located]
        self.state = State(list(seen.atoms()) + kept)
