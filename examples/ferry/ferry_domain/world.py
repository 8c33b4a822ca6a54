"""The true harbour: passengers who balk at the gangway and change their minds (seen)."""

from __future__ import annotations

import random

from nowplan.api import Action, Atom, Domain, State, SymbolicWorld, atom


def change_of_mind(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: a passenger not yet served wants another dock (never the one they wait on)."""
    served = {str(x) for (x,) in state.facts("served")}
    waiting = {str(x): str(dk) for (x, dk) in state.facts("at")}
    wants = sorted((str(x), str(dk)) for (x, dk) in state.facts("wants") if str(x) not in served)
    if not wants:
        return []
    who, old = rng.choice(wants)
    docks = sorted({str(a) for (a, _) in state.facts("lane")} - {old, waiting.get(who, "")})
    if not docks:
        return []
    return [atom("wants", who, old, value=False), atom("wants", who, rng.choice(docks))]


class FerryWorld(SymbolicWorld):
    """A symbolic harbour (failure_prob, exogenous_prob come with it) whose passengers balk at
    boarding with probability ``balk``."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, balk: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=change_of_mind,
                         exogenous_prob=exogenous_prob)
        self.balk = balk

    def fault(self, action: Action) -> str | None:
        if action.name == "board" and self.rng.random() < self.balk:
            return f"passenger {action.args[0]} balks at the gangway"
        return None


__all__ = ["FerryWorld", "change_of_mind"]
