"""The progress guard of both acting loops (issue 14): no loop that only a budget ends.

The plan-stack executive (:mod:`nowplan.acting.hpn`) and the online policy
(:mod:`nowplan.acting.online`) each hold one :class:`ProgressGuard` and are its
:class:`GuardHost`.  After every action :meth:`ProgressGuard.watch` asks, in order:

* did a mechanism give up (:meth:`ProgressGuard.give_up`, e.g. the monitor's escalation)?
* has the same action failed the same way, or have actions made no progress, too often in a row
  (``Strategy.max_stalls``; :class:`~nowplan.acting.progress.CycleDetector`)?
* has a block of 2–8 actions been repeated, each succeeding, with no outside change and no goal
  atom gained (:class:`~nowplan.acting.progress.RepeatedActions`: a loop the fingerprints miss
  because the belief drifts)?
* is the situation (the belief's fingerprint and the plan stack's goals) one held before?  Then a
  cycle is reported to the host (:meth:`GuardHost.after_cycle`); unless it is the clean cycle that
  reaches ``Strategy.max_cycles`` since the last progress (the run then ends as a livelock with the
  cycle named), the host *commits* to its current plans (:meth:`GuardHost.commit`): the
  executive's reconsidering mechanisms (aggressive, selective, serendipity, the monitor) keep them,
  the online policy follows the rest of the plan it acted on instead of replanning.  The situations
  seen before are forgotten: only cycles made while committed count.

Progress — a belief never held before, reached while committed — ends the commitment
(:attr:`ProgressGuard.committed`: the executive's mechanisms reconsider again) and restarts the
count of cycles and of failed cycles, for both hosts (:meth:`GuardHost.end_commitment` names what
that means for the host's trace: the online policy still follows the rest of its plan, until it is
done or its next step is not applicable).  The count of stalls is not restarted: a failure is never
progress.
"""

from __future__ import annotations

from collections.abc import Hashable, Iterable
from typing import TYPE_CHECKING, Any, Protocol

from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.progress import (
    Cycle, CycleDetector, RepeatedActions, failed_cycles_reason, repeated_actions_reason, situation, situation_of,
    stall_reason,
)
from nowplan.core.atoms import Goal
from nowplan.trace import Trace
from nowplan.worlds.base import Observation

if TYPE_CHECKING:
    from nowplan.acting.strategy import Strategy
    from nowplan.core.domain import Domain, Problem
    from nowplan.core.operators import Action


class GuardHost(Protocol):
    """What the guard reads of an acting loop (the executive, the online policy)."""

    @property
    def trace(self) -> Trace: ...
    @property
    def metrics(self) -> Metrics: ...
    @property
    def strategy(self) -> Strategy: ...
    @property
    def domain(self) -> Domain: ...
    @property
    def problem(self) -> Problem: ...
    @property
    def truth(self) -> Any: ...
    @property
    def last_action(self) -> Action | None: ...
    @property
    def last_failed(self) -> tuple[Action, Observation] | None: ...

    @property
    def actor(self) -> str:
        """Who had committed, in a livelock's reason ("the executive", "the policy")."""
        ...

    def situation(self) -> Hashable | None:
        """The guard's situation now (:meth:`ProgressGuard.situation`), or None without a fingerprint."""
        ...

    def after_cycle(self, cyc: Cycle) -> None:
        """A cycle closed (before the guard decides between a livelock and a commitment)."""
        ...

    def commit(self, cyc: Cycle) -> str:
        """Commit to the current plans after ``cyc``; what was committed to, for the trace's note."""
        ...

    def end_commitment(self) -> str:
        """Progress ended the commitment; what that means for the host, for the trace's note."""
        ...


class ProgressGuard:
    """Cycles across actions, repeated blocks of actions, and the commitment after a cycle."""

    def __init__(self, max_cycles: int) -> None:
        self.cycles = CycleDetector(max_cycles)
        self.repeats = RepeatedActions()  # loops the fingerprints miss (a belief that drifts)
        self.committed = False
        self._give_up: tuple[Outcome, str] | None = None  # a mechanism's reason to end the run
        self._beliefs_seen: set[Hashable] = set()  # commitment ends at a belief not seen before

    def give_up(self, outcome: Outcome, reason: str) -> None:
        """A mechanism ends the run after this action with ``reason``."""
        self._give_up = (outcome, reason)

    def forgive(self) -> None:
        """Start the count of cycles and repeated actions again (the executive changed how it plans:
        refine-flat's last resort, after a livelock the hierarchical plans made)."""
        self.cycles.forget(cycles=True)
        self.repeats.reset()
        self.committed = False

    def situation(self, ex: GuardHost, belief: Any, goals: Iterable[Goal]) -> Hashable:
        """The belief's fingerprint and the plan stack's goals; a belief not held before ends a commitment."""
        fp = situation_of(belief)  # (a belief without a fingerprint: a situation never seen before)
        if fp not in self._beliefs_seen:
            self._beliefs_seen.add(fp)
            if self.committed:  # progress: a belief never held before ends the commitment
                self.committed = False
                self.cycles.forget(cycles=True)
                ex.trace.emit("note", text=f"progress: a belief not held before; {ex.end_commitment()}")
        return situation(fp, goals)

    def start(self, ex: GuardHost) -> None:
        """The situation before the first action."""
        start = ex.situation()
        if start is not None:
            self.cycles.start(start)

    def watch(self, ex: GuardHost, obs: Observation) -> tuple[Outcome, str] | None:
        """After an action and the reconsiderations: the run's end (outcome, reason), or None."""
        if self._give_up is not None:
            return self._give_up
        now = ex.situation()
        if now is None:
            return None
        last = ex.last_action
        failure = None if obs.success or last is None else (last.key, obs.info.get("reason"))
        cyc = self.cycles.observe(now, succeeded=obs.success, exogenous=bool(obs.exogenous), failure=failure)
        if self.cycles.stalled >= ex.strategy.max_stalls:
            return Outcome.FAILED, stall_reason(self.cycles.stalled, last, obs)
        if last is not None:
            achieved = ex.domain.count_holding(ex.truth, ex.problem.goal.atoms)
            loop = self.repeats.observe(last.pddl(), succeeded=obs.success,
                                        exogenous=bool(obs.exogenous), achieved=achieved)
            if loop is not None:
                return Outcome.LIVELOCK, repeated_actions_reason(loop[0], loop[1], self.repeats.needed(loop[0]))
        if cyc is None:
            return None
        ex.metrics.cycles = self.cycles.seen
        if self.cycles.failed_cycles >= ex.strategy.max_stalls:
            return Outcome.FAILED, failed_cycles_reason(cyc, self.cycles.failed_cycles, ex.last_failed)
        return self._on_cycle(ex, cyc, now)

    def _on_cycle(self, ex: GuardHost, cyc: Cycle, now: Hashable) -> tuple[Outcome, str] | None:
        ex.trace.emit("cycle", n=cyc.visit, length=cyc.length, count=cyc.count, clean=cyc.clean,
                      text=cyc.describe())
        ex.after_cycle(cyc)
        if cyc.clean and self.cycles.livelocked:
            return Outcome.LIVELOCK, (
                f"livelock: cycle {cyc.count} of at most {self.cycles.max_cycles}: {cyc.describe()}, "
                f"although {ex.actor} had committed to its plan"
            )
        self.committed = True
        self.cycles.forget(keep=now)
        ex.trace.emit("note", text=f"progress: {cyc.describe()}; {ex.commit(cyc)}")
        return None
