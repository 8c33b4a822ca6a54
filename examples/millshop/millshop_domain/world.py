"""The true shop: spoilt turns scrap the blank, spoilt coats smudge the part, machines trip off, and
the shop's status reports may come late (the report of the state before the action)."""

from __future__ import annotations

import random
from typing import Any

from nowplan.api import Action, Atom, Domain, State, SymbolicWorld, atom


def power_trip(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: a machine that is on trips off (seen on the shop's board)."""
    on = sorted(str(x) for (x,) in state.facts("on"))
    return [atom("on", rng.choice(on), value=False)] if on else []


class ShopWorld(SymbolicWorld):
    """A symbolic shop (failure_prob, exogenous_prob come with it) with faults of its own:
    ``scrap`` (a turn spoils the blank: it goes to the scrap bin, for good), ``smudge`` (a coat
    spoils: the part is no longer clean and must be stripped) and ``lag`` (the report after an
    action is the one from before it; the next report is current)."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, scrap: float = 0.0, smudge: float = 0.0, lag: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=power_trip,
                         exogenous_prob=exogenous_prob)
        self.scrap, self.smudge, self.lag = scrap, smudge, lag
        self._last: State = state

    def fault(self, action: Action) -> str | None:
        if action.name == "turn" and self.rng.random() < self.scrap:
            part, station = action.args[0], action.args[1]
            self.state = self.state.apply([atom("raw", part, value=False), atom("at", part, station, value=False),
                                           atom("scrapped", part)])
            return f"turning {part} spoilt it: scrapped"
        if action.name == "paint" and self.rng.random() < self.smudge:
            part = action.args[0]
            self.state = self.state.apply([atom("clean", part, value=False)])
            return f"the coat on {part} smudged: strip it first"
        return None

    def observe(self, action: Action, success: bool) -> Any:
        if self.lag and self.rng.random() < self.lag:
            late = self._last
            self._last = self.state
            return late  # the report of the state before this action (late)
        self._last = self.state
        return self.state


__all__ = ["ShopWorld", "power_trip"]
