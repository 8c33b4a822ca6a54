"""A point belief over a symbolic state: what the agent thinks the state is.

With full observations it adopts the observed state; with outcome-only
observations it applies the action's expected effects when the action is
reported successful (its model may then drift from the world, which is what
the replanning mechanisms are for).  With derived predicates a ``closure``
recomputes the derived atoms after each expected update (an observed state
is the world's, closed already).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Term
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.worlds.base import Observation

if TYPE_CHECKING:
    from nowplan.core.domain import Domain


class SymbolicBelief:
    """A point belief over a symbolic :class:`State` that lists its facts (the common case).

    It offers ``value``, ``facts``/``atoms`` and ``state`` (see
    :mod:`nowplan.belief.protocols`); derive from it to add a domain's own update.
    """

    def __init__(self, state: State, closure: Callable[[State], State] | None = None) -> None:
        self.closure = closure
        self.state = state if closure is None else closure(state)

    def value(self, key: tuple[str, tuple[Term, ...]]) -> Any:
        return self.state.value(key)

    def facts(self, predicate: str) -> list[tuple[Term, ...]]:
        return self.state.facts(predicate)

    def atoms(self) -> Iterator[Atom]:
        return self.state.atoms()

    def update(self, action: Action, observation: Observation) -> None:
        if isinstance(observation.data, State):
            self.state = observation.data
        elif observation.success:
            state = self.state.apply(action.effects())
            self.state = state if self.closure is None else self.closure(state)

    def copy(self) -> SymbolicBelief:
        out = SymbolicBelief(self.state)
        out.closure = self.closure
        return out

    def __repr__(self) -> str:
        return f"SymbolicBelief({self.state!r})"


def truth_of(domain: Domain, belief: Any) -> Any:
    """What goal tests should read: a symbolic belief's state where the domain's truth is plain
    (``Domain.satisfies`` and ``count_holding`` then look each atom up in it), else the belief."""
    return belief.state if type(belief) is SymbolicBelief and domain.plain_truth else belief
