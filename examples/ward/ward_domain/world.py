"""The true ward: staff open and close doors and push the trolley about; the robot sees only its room."""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

from nowplan.api import Action, Atom, Domain, Observation, ParticleBelief, State, SymbolicWorld, atom

from ward_domain.model import LOOKS


@dataclass(frozen=True)
class Seen:
    """What the robot senses after an action: its room, what it holds, the doors of its room as read
    (a door missed by the sensor is absent), and the items lying in its room."""

    room: object
    held: object | None
    doors: tuple[tuple[object, bool], ...]
    items: frozenset[object]


def doors_of(state: State, room: object) -> list[object]:
    return sorted({d for (d, a, _) in state.facts("connects") if a == room}, key=str)


def staff(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: someone opens or shuts a door, or pushes a bulky item through an open door."""
    doors = sorted({str(d) for (d, _, _) in state.facts("connects")})
    if rng.random() < 0.25:
        bulky = {x for (x,) in state.facts("bulky")}
        moves = sorted((str(o), str(r), str(r2)) for (o, r) in state.facts("at") if o in bulky
                       for (d, a, r2) in state.facts("connects") if a == r and state.holds(atom("open", d)))
        if moves:
            o, r, r2 = rng.choice(moves)
            return [atom("at", o, r, value=False), atom("at", o, r2)]
        return []
    d = rng.choice(doors)
    return [atom("open", d, value=not state.holds(atom("open", d)))]


class WardWorld(SymbolicWorld):
    """The robot reads the doors of its room (each misread with probability ``noise``, missed with
    ``miss``) and sees the items in its room; nothing else."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, noise: float = 0.0, miss: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=staff,
                         exogenous_prob=exogenous_prob)
        self.noise, self.miss = noise, miss

    def apply(self, action: Action) -> None:
        if action.name not in LOOKS:  # a look's effect is what the robot hopes to learn
            super().apply(action)

    def observe(self, action: Action, success: bool) -> Any:
        s = self.state
        room = s.facts("robot_in")[0][0]
        held = next((x for (x,) in s.facts("holding")), None)
        doors = []
        for d in doors_of(s, room):
            if self.rng.random() < self.miss:
                continue
            is_open = s.holds(atom("open", d))
            doors.append((d, is_open != (self.rng.random() < self.noise)))
        items = frozenset(o for (o, r) in s.facts("at") if r == room)
        return Seen(room, held, tuple(doors), items)


class WardBelief(ParticleBelief):
    """Particles over the doors' states and where the trolley is; staff may change both unseen."""

    def __init__(self, particles: list[State], *, seed: int, noise: float, flip: float) -> None:
        super().__init__(particles, seed=seed, threshold=0.95)
        self.noise, self.flip = noise, flip

    def predict(self, state: State, action: Action, observation: Observation, rng: random.Random) -> State:
        if observation.success and action.name not in LOOKS:
            state = state.apply(action.effects())
        if rng.random() < self.flip:  # the staff's model: one door toggled, or the trolley pushed
            state = state.apply(staff(state, rng))
        return state

    def likelihood(self, state: State, action: Action, observation: Observation) -> float:
        seen = observation.data
        if not isinstance(seen, Seen):
            return 1.0
        if state.facts("robot_in")[0][0] != seen.room:
            return 0.0
        held = next((x for (x,) in state.facts("holding")), None)
        if held != seen.held:
            return 0.0
        p = 1.0
        for d, is_open in seen.doors:
            p *= (1.0 - self.noise) if state.holds(atom("open", d)) == is_open else self.noise
        for (o, r) in state.facts("at"):
            if (r == seen.room) != (o in seen.items):
                p *= 0.01  # an item seen where the particle has none (or missing): someone moved it
        return p
