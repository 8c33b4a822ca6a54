"""Aggressive replanning withdraws after the guard's cycles (held-out tidy house, heldout14 finding 7).

A commitment ends at the first belief not held before, so replans that undo the agent's work
(pick the book, put it back) cycled again and again, ended only by the run's budget.  After
``WITHDRAW_AFTER`` cycles the mechanism no longer replans from the root.
"""

from __future__ import annotations

from typing import Any

from nowplan.acting.aggressive import WITHDRAW_AFTER, AggressiveReplan
from nowplan.acting.progress import Cycle
from nowplan.trace import Trace


class _Ex:
    def __init__(self) -> None:
        self.trace = Trace()
        self.committed = False
        self.stack: list[Any] = [object(), object()]
        self.replans = 0

    def goal_holds(self) -> bool:
        return False

    def next_step(self, frame: Any) -> Any:
        self.replans += 1
        raise _Replanned


class _Replanned(Exception):
    pass


def _after_action(m: AggressiveReplan, ex: _Ex) -> bool:
    try:
        m.after_action(ex)  # type: ignore[arg-type]
    except _Replanned:
        return True
    return False


def test_withdraws_after_the_guards_cycles() -> None:
    m, ex = AggressiveReplan(), _Ex()
    assert _after_action(m, ex)  # replans after an action while no cycle was seen
    for k in range(WITHDRAW_AFTER):
        assert _after_action(m, ex)  # still replanning below the bound
        m.after_cycle(ex, Cycle(length=2, count=k + 1, first_visit=10 * k, visit=10 * k + 2))  # type: ignore[arg-type]
    assert not _after_action(m, ex)
    assert any("no more replanning" in e.get("text", "") for e in ex.trace.of("note"))
