"""A simulated world for symbolic domains, with seeded failures and exogenous changes.

It keeps its own true :class:`State`, separate from the agent's belief.  An
action whose full (concrete) preconditions are false in the true state, or
that draws a failure, changes nothing and reports ``success=False``.
Exogenous events are drawn after each action from a domain-supplied
function.
"""

from __future__ import annotations

import logging
import random
from collections.abc import Callable
from typing import Literal

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)

ExogenousFn = Callable[[State, random.Random], list[Atom]]


class SymbolicWorld:
    def __init__(
        self,
        domain: Domain,
        state: State,
        *,
        seed: int = 0,
        failure_prob: float = 0.0,
        exogenous: ExogenousFn | None = None,
        exogenous_prob: float = 0.0,
        observe: Literal["full", "outcome"] = "full",
    ) -> None:
        if not 0.0 <= failure_prob <= 1.0 or not 0.0 <= exogenous_prob <= 1.0:
            raise ValueError("failure_prob and exogenous_prob must be in [0, 1]")
        self.domain = domain
        self.state = state
        self.rng = random.Random(seed)
        self.failure_prob = failure_prob
        self.exogenous = exogenous
        self.exogenous_prob = exogenous_prob
        self.observe = observe
        self.failures = 0
        self.exogenous_events = 0

    def true_state(self) -> State:
        """The world's state (for judging success at the end of a run; never for acting)."""
        return self.state

    def applicable(self, action: Action) -> bool:
        return all(self.domain.holds(p, self.state) for p in action.preconditions(None))

    def execute(self, action: Action) -> Observation:
        ok = self.applicable(action)
        info: dict[str, object] = {}
        if not ok:
            info["reason"] = "preconditions false in the world"
        elif self.failure_prob and self.rng.random() < self.failure_prob:
            ok = False
            self.failures += 1
            info["reason"] = "injected failure"
        if ok:
            self.state = self.state.apply(action.effects())
        changes: list[Atom] = []
        if self.exogenous is not None and self.exogenous_prob and self.rng.random() < self.exogenous_prob:
            changes = self.exogenous(self.state, self.rng)
            if changes:
                self.state = self.state.apply(changes)
                self.exogenous_events += 1
        log.debug("world executed %s: success=%s", action, ok)
        data = self.state if self.observe == "full" else None
        return Observation(ok, data, tuple(str(c) for c in changes), info)
