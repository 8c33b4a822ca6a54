"""The true mine (a draining battery, a gate the draught opens, a detector that misses and lies)
and the rover's particle belief over where the gem lies."""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

from nowplan.api import Action, Atom, Domain, Observation, ParticleBelief, State, SymbolicWorld, atom


@dataclass(frozen=True)
class Seen:
    """What the rover sees after an action: every fluent but where the gem lies, and a scan's reading."""

    known: tuple[Atom, ...]
    reading: tuple[str, bool] | None = None  # (place, "the detector beeped") after a scan


def drain_or_draught(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: the battery loses a level (half the time, seen on the gauge), or the
    draught blows the gate open (seen)."""
    if rng.random() < 0.5:
        below = {str(a): str(b) for (a, b) in state.facts("dec")}
        now = [str(x) for (x,) in state.facts("batt")]
        if now and now[0] in below:
            return [atom("batt", now[0], value=False), atom("batt", below[now[0]])]
        return []
    shut = sorted({str(g) for (g, _, _) in state.facts("gated")} - {str(g) for (g,) in state.facts("open")})
    return [atom("open", rng.choice(shut))] if shut else []


def visible(state: State) -> tuple[Atom, ...]:
    return tuple(a for a in state.atoms() if a.predicate != "at")


class MineWorld(SymbolicWorld):
    """A scan beeps where the gem is with probability 1 - ``miss`` and where it is not with
    probability ``fp``; it changes nothing."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, miss: float = 0.0, fp: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=drain_or_draught,
                         exogenous_prob=exogenous_prob)
        self.miss, self.fp = miss, fp

    def apply(self, action: Action) -> None:
        if action.name != "scan":  # its effect, at(o, l), is what the rover hopes to learn
            super().apply(action)

    def observe(self, action: Action, success: bool) -> Any:
        reading = None
        if action.name == "scan" and success:
            place = str(action.args[1])
            there = self.state.holds(atom("at", action.args[0], place))
            reading = (place, self.rng.random() >= self.miss if there else self.rng.random() < self.fp)
        return Seen(visible(self.state), reading)


class MineBelief(ParticleBelief):
    """Particles over where the gem lies; everything else is adopted from what is seen.  ``miss``
    and ``fp`` are the detector's rates as the rover models them; ``doubt`` the chance per step
    and particle that the gem is elsewhere after all (it keeps every place alive through resampling,
    so that a false beep early does not fix the belief for good)."""

    def __init__(self, particles: list[State], places: tuple[str, ...], *, seed: int, miss: float, fp: float,
                 doubt: float = 0.01, threshold: float = 0.95) -> None:
        super().__init__(particles, seed=seed, threshold=threshold)
        self.places, self.miss, self.fp, self.doubt = places, miss, fp, doubt

    def predict(self, state: State, action: Action, observation: Observation, rng: random.Random) -> State:
        seen = observation.data
        if not isinstance(seen, Seen):
            return state
        known = State(list(seen.known))
        hidden = [a for a in state.atoms() if a.predicate == "at"]
        if any(known.holds(atom(p, a.args[0])) for a in hidden for p in ("holding", "stored")):
            hidden = []  # picked: it lies nowhere
        elif hidden and rng.random() < self.doubt:
            hidden = [atom("at", hidden[0].args[0], rng.choice(self.places))]
        return State(list(seen.known) + hidden)

    def likelihood(self, state: State, action: Action, observation: Observation) -> float:
        seen = observation.data
        if not isinstance(seen, Seen):
            return 1.0
        p = 1.0
        if action.name == "pick" and not observation.success:  # the gem was not there, or the grip failed
            p *= 0.2 if state.holds(atom("at", action.args[0], action.args[1])) else 1.0
        if seen.reading is not None:
            place, beeped = seen.reading
            there = state.holds(atom("at", action.args[0], place))
            p *= ((1.0 - self.miss) if beeped else self.miss) if there else (self.fp if beeped else 1.0 - self.fp)
        return p


__all__ = ["MineBelief", "MineWorld", "Seen", "drain_or_draught"]
