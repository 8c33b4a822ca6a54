"""Exogenous changes the agent does not see (held-out tidy house, helper heldout14, finding 6).

``SimulatedWorld.execute`` reported every exogenous change in ``Observation.exogenous``, which the
progress guard and refine-flat take as news, although a change out of the agent's view is none.
``seen()`` lets a world say which changes the agent notices.
"""

from __future__ import annotations

from nowplan.api import Action, Operator, SimulatedWorld, atom


class _Cat(SimulatedWorld):
    def __init__(self, visible: bool) -> None:
        super().__init__(seed=0, exogenous_prob=1.0)
        self.visible = visible
        self.moved = 0

    def apply(self, action: Action) -> None:
        pass

    def exogenous_change(self) -> list[str]:
        self.moved += 1
        return ["on(toy, floor)"]

    def seen(self, changes: list[str]) -> list[str]:
        return changes if self.visible else []


def test_an_unseen_change_is_made_but_not_reported() -> None:
    act = Action(Operator("wait", (), (), (atom("idle"),)), ())
    for visible in (True, False):
        w = _Cat(visible)
        obs = w.execute(act)
        assert w.moved == 1 and w.exogenous_events == 1
        assert obs.exogenous == (("on(toy, floor)",) if visible else ())
