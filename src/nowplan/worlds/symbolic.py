"""A simulated world for symbolic domains, with seeded failures and exogenous changes.

It keeps its own true :class:`State`, separate from the agent's belief.  An
action whose full (concrete) preconditions are false in the true state, or
that draws a failure, changes nothing and reports ``success=False``.
Exogenous events are drawn after each action from a domain-supplied
function.  A domain with derived predicates gives a ``closure`` (e.g.
:class:`nowplan.planning.derived_state.DerivedClosure`): the world recomputes
its derived atoms from the basic facts after every change.
"""

from __future__ import annotations

import random
from collections.abc import Callable
from typing import Any, Literal

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.worlds.base import SimulatedWorld

ExogenousFn = Callable[[State, random.Random], list[Atom]]
Closure = Callable[[State], State]


class SymbolicWorld(SimulatedWorld):
    """The true :class:`State` of a symbolic domain, with failures and exogenous changes.

    ``exogenous(state, rng)`` returns the atoms an exogenous change makes true
    (or false); ``observe="full"`` reports the whole state after each action,
    ``"outcome"`` only success or failure.  ``closure(state)`` (derived predicates) gives the state
    with its derived atoms recomputed; it is applied to the initial state and after every change.
    """

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
        closure: Closure | None = None,
    ) -> None:
        self.domain = domain
        self.closure = closure
        self.state = state if closure is None else closure(state)
        self.exogenous = exogenous
        self.observe_mode = observe
        super().__init__(seed=seed, failure_prob=failure_prob, exogenous_prob=exogenous_prob)

    @property
    def has_exogenous(self) -> bool:
        return self.exogenous is not None

    def true_state(self) -> State:
        """The world's state (for judging success at the end of a run; never for acting)."""
        return self.state

    def applicable(self, action: Action) -> bool:
        """Whether the action's preconditions hold in the true state.  A precondition on a tested
        predicate (``Predicate(test=...)``, a function of the agent's belief, e.g. "the item may be
        there") is a condition on what the agent knows, not on the world: the world skips it."""
        preds = self.domain.predicates
        return all(self.domain.holds(p, self.state) for p in action.preconditions(None)
                   if (pr := preds.get(p.predicate)) is None or pr.test is None)

    def refuse(self, action: Action) -> str | None:
        return None if self.applicable(action) else "preconditions false in the world"

    def apply(self, action: Action) -> None:
        self.state = self._closed(self.state.apply(action.effects()))

    def _closed(self, state: State) -> State:
        return state if self.closure is None else self.closure(state)

    def exogenous_change(self) -> list[str]:
        if self.exogenous is None:
            return []
        changes = self.exogenous(self.state, self.rng)
        if changes:
            self.state = self._closed(self.state.apply(changes))
        return [str(c) for c in changes]

    def observe(self, action: Action, success: bool) -> Any:
        return self.state if self.observe_mode == "full" else None
