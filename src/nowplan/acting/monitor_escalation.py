"""When the expected-vs-observed monitor stops restoring and replans to the goal (seed 003).

Seed 003's ``Replanner()`` chooses among three ways after a surprise: go to a
stored intermediate state, plan back to the expected model ("backtrack"), or
plan from the observed model to the goal.  Its thresholds assume small,
occasional disturbances.  When the world keeps changing, restoring is a loop:
the agent carries a package back where it was expected, the world moves it
again, and the agent carries it back again.  The progress guard
(:mod:`nowplan.acting.progress`) does not count such a loop, since the world
takes part in it; and a loop the guard does count can live *inside* a
monitor's repair plan, so the executive's commitment to its plans repeats it.

The monitor therefore commits to the seed's third way, replanning to the goal,
for the rest of the run (*escalates*) when either

* the progress guard reports a cycle (:meth:`Monitor.after_cycle`): the repair
  plans on the stack are replaced by a plan to the goal at once; or
* a repair would go back to a model (a restore's or intermediate state's
  target) that the agent's own actions had already reached and the world took
  away again: the world undoes the repairs.

"Reached by the agent's own actions" is judged on the expected model (the model
before the action with its effects applied), so a change the world makes in the
same step still counts as undoing it.  The reason is traced (a ``note`` event
with an ``escalation`` field) and kept in :class:`MonitorStats.escalated`.

When no recovery exists (the world undoes the goal itself), replanning to the goal is a
loop too.  The monitor counts the times the agent's own action completed the goal (in
the expected model) and the world took it away in the same step; at ``Strategy.max_stalls``
of them (default 25: a chance of 0.5**25 where the world undoes it half the time) it ends
the run as failed, with that reason, instead of leaving it to a budget.
"""

from __future__ import annotations

import logging
from typing import TYPE_CHECKING

from nowplan.acting.metrics import Outcome
from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.state import State

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive

log = logging.getLogger(__name__)


class Escalation:
    """The repair targets the monitor went back to, and whether it has escalated (and why)."""

    def __init__(self) -> None:
        self.reason = ""  # "" until the monitor escalates
        self._pending: set[Goal] = set()  # targets chosen, not reached yet
        self._reached: set[Goal] = set()  # targets the agent's own actions reached
        self.goal_undone_count = 0  # the goal completed by the agent and undone by the world at once

    @property
    def escalated(self) -> bool:
        return bool(self.reason)

    def chose(self, target: Goal | None) -> None:
        """A restore or intermediate repair toward ``target`` was applied."""
        if target is not None and target not in self._reached:
            self._pending.add(target)

    def note(self, domain: Domain, expected: State) -> None:
        """After an action: the targets its expected model satisfies were reached by the agent."""
        done = {g for g in self._pending if domain.satisfies(expected, g)}
        self._pending -= done
        self._reached |= done

    def undone(self, target: Goal | None) -> bool:
        """Was ``target`` reached before (so going back to it again chases the world)?"""
        return target is not None and target in self._reached

    def goal_undone(self, ex: Executive, expected: State) -> bool:
        """Did the world undo the goal the agent's action just completed?  Ends the run at the bound."""
        if not ex.last_observation.success or not ex.domain.satisfies(expected, ex.problem.goal) \
                or ex.goal_holds():
            return False  # a failed action is no undoing by the world
        self.goal_undone_count += 1
        ex.trace.emit("note", text=f"monitor: the world undid the goal right after the agent reached it "
                      f"({self.goal_undone_count} time(s))")
        if self.goal_undone_count >= ex.strategy.max_stalls:
            ex.give_up(Outcome.FAILED, (
                f"the world undid the goal {self.goal_undone_count} times right after the agent's own action "
                "completed it; that is not chance: no recovery keeps the goal in this world"))
            return True
        return False

    def escalate(self, ex: Executive, decision: str, why: str) -> None:
        self.reason = why
        text = (f"monitor: escalates from '{decision}' to replanning to the goal after every surprise "
                f"for the rest of the run: {why}")
        log.info(text)
        ex.trace.emit("note", text=text, escalation=why)
