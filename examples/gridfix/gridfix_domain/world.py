"""The true feeder (storm damage, breakers that trip onto a fault, new faults and a draining
battery) and the crew's particle belief over which segments are intact."""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any

from nowplan.api import Action, Atom, Domain, Observation, ParticleBelief, State, SymbolicWorld, atom

from gridfix_domain.model import LOOKS


@dataclass(frozen=True)
class Seen:
    """What the crew knows after an action: every fluent but ``ok`` (where the van is, its battery,
    its spares, and the feeder's telemetry: which junctions are live), and an inspection's reading."""

    known: tuple[Atom, ...]
    reading: tuple[str, bool] | None = None  # (segment, "the detector shows a fault") after an inspect


def downstream(state: State, site: object) -> list[object]:
    """The junctions fed (directly or not) from ``site``, ``site`` excluded."""
    out: list[object] = []
    todo = [site]
    while todo:
        x = todo.pop()
        for (_, u, w) in state.facts("feeds"):
            if u == x:
                out.append(w)
                todo.append(w)
    return out


def path_to(state: State, site: object) -> list[object]:
    """The segments from the substation to ``site`` (the feeder is radial: one path)."""
    feeder = {w: (cc, u) for (cc, u, w) in state.facts("feeds")}
    out: list[object] = []
    while site in feeder:
        cc, site = feeder[site]
        out.append(cc)
    return out


def breaks(state: State, seg: object) -> list[Atom]:
    """The changes when segment ``seg`` breaks: it is no longer intact, and what it fed goes dead."""
    fed = next(w for (cc, _, w) in state.facts("feeds") if cc == seg)
    return [atom("ok", seg, value=False)] + [atom("live", x, value=False) for x in [fed, *downstream(state, fed)]
                                             if state.holds(atom("live", x))]


def weather(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: half the time a gust breaks an intact segment (its breaker opens, what it fed
    goes dead: the telemetry shows that, not which segment), else the battery loses a level (seen)."""
    if rng.random() < 0.5:
        intact = sorted(str(x) for (x,) in state.facts("ok"))
        return breaks(state, rng.choice(intact)) if intact else []
    below = {str(x): str(y) for (x, y) in state.facts("dec")}
    now = [str(x) for (x,) in state.facts("batt")]
    if now and now[0] in below:
        return [atom("batt", now[0], value=False), atom("batt", below[now[0]])]
    return []


def visible(state: State) -> tuple[Atom, ...]:
    return tuple(x for x in state.atoms() if x.predicate != "ok")


class GridWorld(SymbolicWorld):
    """The detector shows a fault on a broken segment with probability 1 - ``miss`` and on an intact
    one with probability ``fp``; closing onto a broken segment trips (the action fails)."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, miss: float = 0.0, fp: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=weather,
                         exogenous_prob=exogenous_prob)
        self.miss, self.fp = miss, fp

    def refuse(self, action: Action) -> str | None:
        if action.name == "close" and not self.state.holds(atom("ok", action.args[0])):
            if self.applicable_but_ok(action):
                return f"breaker trips: closing {action.args[0]} onto a fault"
        return super().refuse(action)

    def applicable_but_ok(self, action: Action) -> bool:
        return all(self.state.holds(p) for p in action.preconditions(None)
                   if p.predicate not in ("ok", "maybe_ok"))

    def apply(self, action: Action) -> None:
        if action.name not in LOOKS:  # an inspection's effect, ok(c), is what the crew hopes to learn
            super().apply(action)

    def observe(self, action: Action, success: bool) -> Any:
        reading = None
        if action.name == "inspect" and success:
            seg = str(action.args[0])
            intact = self.state.holds(atom("ok", seg))
            reading = (seg, self.rng.random() < self.fp if intact else self.rng.random() >= self.miss)
        return Seen(visible(self.state), reading)

    def seen(self, changes: list[str]) -> list[str]:
        """The telemetry and the gauge show dead junctions and a lower battery, not the broken segment."""
        return [x for x in changes if not x.startswith(("ok(", "not ok(", "¬ok("))]


class GridBelief(ParticleBelief):
    """Particles over which segments are intact; everything else is adopted from what is seen.

    ``miss``/``fp`` are the detector's rates as the crew models them, ``trip`` the chance that a
    close fails on an intact segment (a fault of the breaker, not of the line), ``gust`` the chance
    per step that some intact segment breaks unseen, ``doubt`` the chance per step and particle that
    a segment's state is other than believed (keeps every hypothesis alive through resampling)."""

    def __init__(self, particles: list[State], *, seed: int, miss: float, fp: float, trip: float,
                 gust: float, doubt: float = 0.005, threshold: float = 0.9) -> None:
        super().__init__(particles, seed=seed, threshold=threshold)
        self.miss, self.fp, self.trip, self.gust, self.doubt = miss, fp, trip, gust, doubt

    def predict(self, state: State, action: Action, observation: Observation, rng: random.Random) -> State:
        seen = observation.data
        if not isinstance(seen, Seen):
            return state
        known = State(list(seen.known))
        intact = {x for (x,) in state.facts("ok")}
        segments = sorted({x for (x, _, _) in known.facts("feeds")}, key=str)
        if action.name == "replace" and observation.success:
            intact.add(action.args[0])
        # a junction that was live and is dead now, while what feeds it is still live: its segment broke
        for (cc, u, w) in known.facts("feeds"):
            if state.holds(atom("live", w)) and not known.holds(atom("live", w)) and known.holds(atom("live", u)):
                intact.discard(cc)
        if self.gust and intact and rng.random() < self.gust:
            intact.discard(rng.choice(sorted(intact, key=str)))
        if self.doubt and rng.random() < self.doubt:
            intact ^= {rng.choice(segments)}
        return State(list(seen.known) + [atom("ok", x) for x in sorted(intact, key=str)])

    def likelihood(self, state: State, action: Action, observation: Observation) -> float:
        seen = observation.data
        if not isinstance(seen, Seen):
            return 1.0
        p = 1.0
        if action.name == "close" and not observation.success:
            p *= self.trip if state.holds(atom("ok", action.args[0])) else 1.0
        if seen.reading is not None:
            seg, alarm = seen.reading
            intact = state.holds(atom("ok", seg))
            p *= (self.fp if alarm else 1.0 - self.fp) if intact else ((1.0 - self.miss) if alarm else self.miss)
        for (w,) in state.facts("live"):  # a live junction: every segment on its path is intact
            if any(not state.holds(atom("ok", x)) for x in path_to(state, w)):
                p *= 0.01
        return p


__all__ = ["GridBelief", "GridWorld", "Seen", "breaks", "downstream", "path_to", "visible", "weather"]
