"""The world interface: where actions are executed and observations come from.

The agent never reads the world's state; it only receives observations
(pomdp_py's separation of the agent's model from the true simulator).  A
real robot or another simulator plugs in by implementing :class:`World`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Protocol, runtime_checkable

from nowplan.core.operators import Action


@dataclass(frozen=True)
class Observation:
    """What the world reports after an action.

    ``success`` says whether the action ran as commanded (a gripper may report a
    missed grasp); ``data`` is domain-specific (for symbolic worlds, observed
    fluent values); ``exogenous`` lists changes the world made by itself that the
    agent could see, as human-readable strings for the trace.
    """

    success: bool = True
    data: Any = None
    exogenous: tuple[str, ...] = ()
    info: dict[str, Any] = field(default_factory=dict, hash=False, compare=False)


@runtime_checkable
class World(Protocol):
    def execute(self, action: Action) -> Observation: ...


@runtime_checkable
class Inspectable(Protocol):
    """A simulated world that can tell its true state, so that success is judged in the world.

    ``true_state()`` returns something the domain's predicates can test (for symbolic worlds
    a :class:`~nowplan.core.state.State`).  The executive asks it only at the end of a run: an
    outcome ``reached`` then means the goal holds in the world, and the run result reports the
    goal's atoms on which belief and world disagree.  The agent never reads it while acting.
    """

    def true_state(self) -> Any: ...


@runtime_checkable
class Belief(Protocol):
    """The agent's belief: tested by the domain's predicates, updated by observations."""

    def update(self, action: Action, observation: Observation) -> None: ...
