"""The true room, the robot's sensor (it may miss what is there, never sees what is not), and its belief."""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

from nowplan.api import Action, Atom, Domain, Observation, ParticleBelief, State, SymbolicWorld, atom


@dataclass(frozen=True)
class Seen:
    """What the robot senses after an action: where it is, what it holds, what a look found there."""

    robot: object
    held: object | None
    found: frozenset[object] = frozenset()
    looked: bool = False


def knock(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: someone moves a loose item to another place (not the base)."""
    loose = sorted((str(x), str(p)) for (x, p) in state.facts("at"))
    bases = {b for (b,) in state.facts("base")}
    places = sorted({str(a) for (a, _) in state.facts("adjacent")} - {str(b) for b in bases})
    if not loose:
        return []
    x, p = rng.choice(loose)
    to = rng.choice(places)
    return [] if to == p else [atom("at", x, p, value=False), atom("at", x, to)]


class SearchWorld(SymbolicWorld):
    """Looks find each item at the robot's place with probability 1 - ``miss``; a look changes nothing."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, miss: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=knock,
                         exogenous_prob=exogenous_prob)
        self.miss = miss

    def apply(self, action: Action) -> None:
        if action.name != "look":  # the model's effect of a look, at(o, l), is what it hopes to learn
            super().apply(action)

    def observe(self, action: Action, success: bool) -> Any:
        here = self.state.facts("robot_at")[0][0]
        held = next((x for (x,) in self.state.facts("holding")), None)
        if action.name != "look" or not success:
            return Seen(here, held)
        there = {x for (x, p) in self.state.facts("at") if p == here}
        return Seen(here, held, frozenset(x for x in sorted(there, key=str) if self.rng.random() >= self.miss), True)


class SearchBelief(ParticleBelief):
    """Particles over where the items lie; the sensor model knows the miss rate; items may be moved."""

    def __init__(self, particles: list[State], *, seed: int, miss: float, moved: float = 0.02,
                 failure: float = 0.3) -> None:
        super().__init__(particles, seed=seed)
        self.miss, self.moved, self.failure = miss, moved, failure

    def predict(self, state: State, action: Action, observation: Observation, rng: random.Random) -> State:
        if action.name == "look":
            pass
        elif action.name == "pick" and observation.success:
            item = action.args[0]
            state = state.apply([atom("at", item, p, value=False) for (x, p) in state.facts("at") if x == item]
                                + [atom("holding", item), atom("hand_empty", value=False)])
        elif observation.success:
            state = state.apply(action.effects())
        if self.moved and rng.random() < self.moved:  # someone may have moved a loose item
            state = state.apply(knock(state, rng))
        return state

    def likelihood(self, state: State, action: Action, observation: Observation) -> float:
        seen = observation.data
        if not isinstance(seen, Seen):
            return 1.0
        if state.facts("robot_at")[0][0] != seen.robot:
            return 0.0
        p = 1.0
        if action.name == "pick" and not observation.success:
            # a pick fails when the item is not there, or now and then when it is
            p *= self.failure if state.holds(atom("at", action.args[0], action.args[1])) else 1.0
        if seen.looked:
            for (x, where) in state.facts("at"):
                if where == seen.robot:
                    p *= (1.0 - self.miss) if x in seen.found else self.miss
                elif x in seen.found:
                    p *= 0.01  # not believed there, yet seen: someone moved it (all-zero weights learn nothing)
        return p
