"""Strategy switches and the mechanisms behind them.

A *switch* is a name a user puts in a strategy string (``hpn+aggressive``).
It may set fields of :class:`nowplan.acting.strategy.Strategy` and/or add a
:class:`Mechanism`: an object whose hooks the executive calls at fixed
points of the plan-stack loop.  Each seed mechanism is one small module that
registers its switch here; the executive never names them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame
    from nowplan.acting.progress import Cycle
    from nowplan.core.atoms import Goal
    from nowplan.planning.regression import PlannerConfig
    from nowplan.planning.plan import PlanResult, PlanStep


class Mechanism:
    """Hooks a strategy switch can override; each default means "no opinion"."""

    name = "mechanism"

    def check(self, ex: Executive) -> None:
        """Refuse, when the executive is built and before anything runs, a domain or belief this
        mechanism cannot work with (raise :class:`~nowplan.errors.ScenarioError` with the fix)."""

    def applicable(self, ex: Executive, frame: Frame) -> bool | None:
        """Decide whether the top plan is still applicable (None: use the rigid test)."""
        return None

    def next_step(self, ex: Executive, frame: Frame) -> PlanStep | None:
        """Choose the frame's next step, advancing ``frame.i`` (None: the sequentially next)."""
        return None

    def after_action(self, ex: Executive) -> None:
        """Reconsider the plan stack after an action and belief update."""

    def after_push(self, ex: Executive, frame: Frame) -> None:
        """A new plan was pushed."""

    def planner_config(
        self, ex: Executive, parent: Frame, goal: Goal, config: PlannerConfig
    ) -> PlannerConfig | None:
        """The planner configuration for the plan about to be made for ``goal`` (None: keep)."""
        return None

    def after_plan_failure(self, ex: Executive, parent: Frame, goal: Goal, result: PlanResult) -> None:
        """The planner found no plan for ``goal``, the subgoal of ``parent``'s current step."""

    def after_cycle(self, ex: Executive, cycle: Cycle) -> None:
        """The progress guard found a cycle (before the executive commits or ends the run)."""


MechanismFactory = Callable[[Any], Mechanism]  # Strategy -> Mechanism


@dataclass(frozen=True)
class Switch:
    name: str
    description: str
    fields: Mapping[str, Any] = field(default_factory=dict)  # Strategy fields it sets
    planner: Mapping[str, Any] = field(default_factory=dict)  # PlannerConfig fields it sets
    mechanism: MechanismFactory | None = None


SWITCHES: dict[str, Switch] = {}


def register_switch(switch: Switch) -> Switch:
    SWITCHES[switch.name] = switch
    return switch
