"""The true greenhouse: a leaking tank, pests that land on plants, a noisy pest sensor, and the
particle belief of the robots (what they see of the world, and the odds of pests on each plant)."""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

from nowplan.api import Action, Atom, Domain, Observation, ParticleBelief, State, SymbolicWorld, atom

from greenhouse_domain.model import dist


@dataclass(frozen=True)
class Seen:
    """What the robots see after an action: every fluent but the pests, and an inspection's reading."""

    known: tuple[Atom, ...]
    reading: tuple[str, bool] | None = None  # (plant, "looks clean") after an inspection


def leak_or_pest(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: the tank loses a level (half the time), or pests land on an unwatered plant."""
    if rng.random() < 0.5:
        levels = sorted(str(x) for (x,) in state.facts("level"))
        below = {str(a): str(b) for (a, b) in state.facts("dec") if str(a).startswith("l")}
        if levels and levels[0] in below:
            return [atom("level", levels[0], value=False), atom("level", below[levels[0]])]
        return []
    plants = sorted(str(x) for (x, _) in state.facts("spot") if not state.holds(atom("watered", x)))
    return [atom("clean", rng.choice(plants), value=False)] if plants else []


def visible(state: State) -> tuple[Atom, ...]:
    return tuple(a for a in state.atoms() if a.predicate != "clean")


class GreenhouseWorld(SymbolicWorld):
    """An inspection reads the plant wrong with probability ``noise`` and changes nothing; a robot
    cannot drive onto the pose the other robot stands on."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, noise: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=leak_or_pest,
                         exogenous_prob=exogenous_prob)
        self.noise = noise

    def refuse(self, action: Action) -> str | None:
        if action.name == "drive":
            robot, to = action.args
            for (other,) in self.state.facts("robot"):
                if other != robot and self.state.value(("pose", (other,))) == to:
                    return f"pose {to} is taken by {other}"
        return super().refuse(action)

    def apply(self, action: Action) -> None:
        if action.name != "inspect":  # its effect, clean(p), is what the robots hope to learn
            super().apply(action)

    def observe(self, action: Action, success: bool) -> Any:
        reading = None
        if action.name == "inspect" and success:
            plant = str(action.args[1])
            truth = self.state.holds(atom("clean", plant))
            reading = (plant, truth if self.rng.random() >= self.noise else not truth)
        return Seen(visible(self.state), reading)


class GreenhouseBelief(ParticleBelief):
    """Particles over which plants are clean; everything else is adopted from what is seen.
    ``noise`` is the sensor's error rate, ``spread`` the chance per step that pests land on a given
    unwatered plant (the world's exogenous rate over twice the number of plants)."""

    def __init__(self, particles: list[State], *, seed: int, noise: float, spread: float) -> None:
        super().__init__(particles, seed=seed, threshold=0.9)
        self.noise, self.spread = noise, spread

    def predict(self, state: State, action: Action, observation: Observation, rng: random.Random) -> State:
        seen = observation.data
        clean = [a for a in state.atoms() if a.predicate == "clean"]
        if action.name == "spray" and observation.success:
            clean.append(atom("clean", action.args[1]))
        new = State(list(seen.known) + clean) if isinstance(seen, Seen) else state
        if self.spread:
            gone = [atom("clean", x, value=False) for (x, _) in new.facts("spot")
                    if new.holds(atom("clean", x)) and not new.holds(atom("watered", x))
                    and rng.random() < self.spread]
            new = new.apply(gone)
        return new

    def likelihood(self, state: State, action: Action, observation: Observation) -> float:
        seen = observation.data
        if not isinstance(seen, Seen) or seen.reading is None:
            return 1.0
        plant, looks_clean = seen.reading
        return 1.0 - self.noise if state.holds(atom("clean", plant)) == looks_clean else max(self.noise, 0.01)


__all__ = ["GreenhouseBelief", "GreenhouseWorld", "Seen", "dist", "leak_or_pest"]
