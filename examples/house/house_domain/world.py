"""The simulated house: the true state, with sticky doors and a draught that closes doors."""

from __future__ import annotations

import random

from nowplan.api import Action, Atom, Domain, State, SymbolicWorld, atom


def draught(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: a draught shuts one open door."""
    doors = sorted(str(a[0]) for a in state.facts("open"))
    return [atom("open", rng.choice(doors), value=False)] if doors else []


class HouseWorld(SymbolicWorld):
    """A symbolic world (failure_prob, exogenous_prob come with it) whose doors may stick."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, sticky: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=draught,
                         exogenous_prob=exogenous_prob)
        self.sticky = sticky  # the probability that opening a door fails

    def fault(self, action: Action) -> str | None:
        if action.name == "open_door" and self.rng.random() < self.sticky:
            return f"door {action.args[0]} is stuck"
        return None
