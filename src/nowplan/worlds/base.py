"""The world interface: where actions are executed and observations come from.

The agent never reads the world's state; it only receives observations
(pomdp_py's separation of the agent's model from the true simulator).  A
real robot or another simulator plugs in by implementing :class:`World`.
"""

from __future__ import annotations

import logging
import random
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


log = logging.getLogger(__name__)


@runtime_checkable
class World(Protocol):
    """What the executive needs from a world: execute an action, report an observation."""

    def execute(self, action: Action) -> Observation: ...


@runtime_checkable
class FaultInjection(Protocol):
    """A world whose faults can be set after it is made (``nowplan run --failure-prob/--exogenous-prob``).

    ``set_faults`` raises ``ValueError`` with a one-line reason for a fault the
    world cannot inject (e.g. exogenous changes in a world that has none).
    """

    def set_faults(self, *, failure_prob: float | None = None, exogenous_prob: float | None = None) -> None: ...


class SimulatedWorld:
    """A base for simulated worlds, with fault injection for every domain.

    The constructor takes the faults: ``failure_prob``, the probability that an
    applicable action does nothing and reports failure, and ``exogenous_prob``,
    the probability that after an action the world changes by itself.  Every
    draw comes from ``self.rng`` (seeded by ``seed``).  A subclass provides:

    * :meth:`refuse` — why the action cannot run in the true state (``None``: it can);
    * :meth:`apply` — run it (change the true state);
    * :meth:`fault` — optionally, a fault of the domain's own (a sticky door), drawn from ``self.rng``;
    * :meth:`exogenous_change` — optionally, change the world by itself; returns what changed, as text;
      :attr:`has_exogenous` says whether it can; :meth:`seen` which of the changes the agent notices;
    * :meth:`observe` — the observation's ``data`` after an action (default ``None``).
    """

    def __init__(self, *, seed: int = 0, failure_prob: float = 0.0, exogenous_prob: float = 0.0) -> None:
        self.rng = random.Random(seed)
        self.failure_prob = 0.0
        self.exogenous_prob = 0.0
        self.failures = 0
        self.exogenous_events = 0
        self.asked: list[Action] = []  # every action asked of the world, in order, whether it ran or not
        self.set_faults(failure_prob=failure_prob, exogenous_prob=exogenous_prob)

    def set_faults(self, *, failure_prob: float | None = None, exogenous_prob: float | None = None) -> None:
        for name, p in (("failure_prob", failure_prob), ("exogenous_prob", exogenous_prob)):
            if p is not None and not 0.0 <= p <= 1.0:
                raise ValueError(f"{name} must be in [0, 1], got {p}")
        if exogenous_prob and not self.has_exogenous:
            raise ValueError(f"{type(self).__name__} makes no exogenous changes (a PDDL problem has none); drop it, or use a scenario that has them")
        if failure_prob is not None:
            self.failure_prob = failure_prob
        if exogenous_prob is not None:
            self.exogenous_prob = exogenous_prob

    # -- what a subclass provides ---------------------------------------------------------
    @property
    def has_exogenous(self) -> bool:
        """Whether this world can change by itself (default: it defines :meth:`exogenous_change`)."""
        return type(self).exogenous_change is not SimulatedWorld.exogenous_change

    def refuse(self, action: Action) -> str | None:
        return None

    def apply(self, action: Action) -> None:
        raise NotImplementedError(f"{type(self).__name__} must define apply(action)")

    def fault(self, action: Action) -> str | None:
        return None

    def exogenous_change(self) -> list[str]:
        return []

    def observe(self, action: Action, success: bool) -> Any:
        return None

    def seen(self, changes: list[str]) -> list[str]:
        """The exogenous changes just made that the agent notices (``Observation.exogenous``; default:
        all).  A world whose changes can happen out of the agent's view returns fewer: the change is
        made all the same, and the belief learns of it only through what :meth:`observe` shows (the
        progress guard and refine-flat treat a reported change as news, an unseen one as none)."""
        return changes

    # -- the loop --------------------------------------------------------------------------
    def execute(self, action: Action) -> Observation:
        self.asked.append(action)
        info: dict[str, Any] = {}
        why = self.refuse(action)
        if why is None and self.failure_prob and self.rng.random() < self.failure_prob:
            why = "injected failure"
            self.failures += 1
        if why is None:
            why = self.fault(action)
            if why is not None:
                self.failures += 1
        if why is None:
            self.apply(action)
        else:
            info["reason"] = why
        changes: list[str] = []
        if self.has_exogenous and self.exogenous_prob and self.rng.random() < self.exogenous_prob:
            changes = self.exogenous_change()
            if changes:
                self.exogenous_events += 1
        log.debug("world executed %s: %s", action, why or "success")
        return Observation(why is None, self.observe(action, why is None), tuple(self.seen(changes) if changes else ()),
                           info)


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
