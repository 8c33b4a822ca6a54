"""The progress guarantee: detect cycles across actions and say when a run is a livelock.

The budgets (actions, planner calls, time) bound every run, but a budget alone says
nothing about *why* a run did not finish.  The mechanisms that reconsider the plan
stack (aggressive and selective replanning, serendipity, the monitor) can each undo
the agent's own work: replan toward another item after every action and shuttle
between two rooms, or resume an earlier step and drop the sub-plan that fetched a key.
Such a loop keeps taking actions, so the executive's "no progress" guard (refinements
without an action) never fires.

This module watches the agent's *situation* after every action: a fingerprint of the
belief (its facts) together with the goals of the plan stack.  A **cycle** is a return
to a situation seen before such that, since that earlier visit,

* at least one action succeeded (failed actions change nothing, so retrying a sticky
  door is not a cycle), and
* the world reported no exogenous change (a package carried back by somebody else
  is the world's doing, not the strategy's).

Only the agent's own choices can then have brought it back.  A cycle in which an action
failed is often HPN's failure-driven replanning choosing another order (a re-grasp that
undoes a placement); a cycle with no failure at all is the strategy undoing its own work.
The executive answers every cycle by *committing* to its current plans (the reconsidering mechanisms
hold off until the belief is one never held before — progress — however the plans
fare meanwhile: hysteresis, as SS-Replan constrains replanning to the previous plan so
that it makes progress; the online policy executes the rest of its last plan).  The
situations seen before the commitment are forgotten: retracing them under the committed
plans is not a new cycle, but a cycle made while committed is, and the run ends with
:attr:`~nowplan.acting.metrics.Outcome.LIVELOCK` and the cycle's description when cycles
with no failed action reach ``max_cycles`` (default 3) without progress or an exogenous change in between.

A loop can also stand still: an action that fails again and again and leaves the
situation as it was (a door the belief thinks open, in a world that reports outcomes
only), or fails the same way each time while the belief drifts on its own (a drone whose
position estimate spreads a little every step, in gusts it does not feel, tried the same
flight 114 times, each refused with "battery too low").  Retrying is right while failures are chance; ``stalled`` counts the failures in a
row, and the executive gives up with its reason at ``Strategy.max_stalls`` (default 25: a
chance of 0.5**25, about 3e-8, at a 50 % failure rate).  Likewise a loop whose every
round has a failed action (re-grasp an object, drag it, the drag stopped by a wall, the
same plan again) never makes a clean cycle: ``failed_cycles`` counts the cycles with a
failure since the last progress, and the executive gives up at ``Strategy.max_stalls`` of
them with its reason (:func:`failed_cycles_reason`) — the failures recur in the same
situations, so they are not chance — instead of running into a budget.
"""

from __future__ import annotations

import logging
from collections.abc import Hashable, Iterable
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

from nowplan.belief.protocols import HasState, offers
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)


@runtime_checkable
class Fingerprinted(Protocol):
    """A belief that can say which situation it is in (equal fingerprints = same belief)."""

    def fingerprint(self) -> Hashable: ...


class Unseen:
    """A situation that never equals another: the fingerprint of a belief that has none.

    With it the guard cannot see cycles, but still counts an action that fails the same way
    again and again (:meth:`CycleDetector.observe`'s ``failure``)."""

    __slots__ = ()


def situation_of(belief: Any) -> Hashable:
    """:func:`belief_fingerprint`, or a fresh :class:`Unseen` when the belief has none."""
    fp = belief_fingerprint(belief)
    return Unseen() if fp is None else fp


def blind_guard_warning(belief: Any) -> str | None:
    """A warning when the progress guard cannot tell the belief's situations apart (None: it can)."""
    if belief_fingerprint(belief) is not None:
        return None
    return (f"the belief {type(belief).__name__} has neither fingerprint() nor a State as .state: the "
            "progress guard sees no cycles (only an action failing the same way again and again); "
            "define fingerprint() (see nowplan.api.Fingerprinted)")


def start_warnings(problem: Any, belief: Any) -> str:
    """Log what a run is about to miss (a blind progress guard, an operator parameter that can never
    bind a value the belief holds); returns the latter as "; ..." for "no plan for the goal", or ""."""
    from nowplan.core.unbound import unbindable_parameters

    blind = blind_guard_warning(belief)
    if blind is not None:
        log.warning(blind)
    hint = unbindable_parameters(problem.domain, problem.all_objects, belief)
    if hint is not None:
        log.warning(hint)
    return f"; {hint}" if hint else ""


def belief_fingerprint(belief: Any) -> Hashable | None:
    """The belief's fingerprint: its own, or its point state's facts; None when it has neither."""
    if offers(belief, Fingerprinted):
        return belief.fingerprint()  # type: ignore[no-any-return]
    if isinstance(belief, State):
        return belief
    if offers(belief, HasState) and isinstance(belief.state, State):
        return belief.state  # a symbolic belief keeps its facts as a State
    return None


@dataclass(frozen=True)
class Cycle:
    """A situation reached again by the agent's own actions."""

    length: int  # actions since the earlier visit
    count: int  # cycles with no failed action since progress (this one included if clean)
    first_visit: int  # the action count at the earlier visit
    visit: int  # the action count now
    clean: bool = True  # no action failed in the cycle

    def describe(self) -> str:
        return (
            f"the belief and the plan stack's goals after action {self.visit} are those after action "
            f"{self.first_visit}, reached again by the agent's own actions ({self.length} action(s), "
            f"no exogenous change{', no failure' if self.clean else ', some failed'} in between)"
        )


class CycleDetector:
    """Remembers situations by fingerprint; reports a :class:`Cycle` on a clean return."""

    def __init__(self, max_cycles: int = 3) -> None:
        if max_cycles < 1:
            raise ValueError("max_cycles must be >= 1")
        self.max_cycles = max_cycles
        self.cycles = 0  # cycles with no failed action (they count toward a livelock)
        self.failed_cycles = 0  # cycles with a failed action since progress
        self.seen = 0  # every cycle
        self._t = 0
        self._last_visit: dict[Hashable, int] = {}
        self._last_success = -1  # action count of the last successful action
        self._last_exogenous = -1  # action count of the last exogenous change
        self._last_failure = -1  # action count of the last failed action
        self.stalled = 0  # failed actions in a row that left the situation as it was (or failed the same way)
        self._prev: Hashable | None = None
        self._prev_failure: Hashable | None = None

    def start(self, situation: Hashable) -> None:
        """The situation before the first action."""
        self._last_visit[situation] = 0
        self._prev = situation

    def observe(self, situation: Hashable, *, succeeded: bool, exogenous: bool,
                failure: Hashable | None = None) -> Cycle | None:
        """The situation after one more action; a :class:`Cycle` if it closes one.

        ``failure`` names a failed action and how it failed (e.g. its key and the world's reason): the
        same action failing the same way again counts toward :attr:`stalled` even when the belief's
        fingerprint drifted meanwhile (a belief that grows less sure with every step never repeats
        one, and a world that changes by itself now and then never leaves one as it was)."""
        self._t += 1
        if succeeded:
            self._last_success = self._t
        else:
            self._last_failure = self._t
        if exogenous:
            self._last_exogenous = self._t
            # the world changed by itself: the cycles counted so far are not one loop of the agent's
            # any more (a lab door the world shut each time the robot opened it made the robot redo
            # its set-down three times: three cycles, each after the world's change, not a livelock)
            self.cycles = 0
        same = not succeeded and (situation == self._prev or (failure is not None and failure == self._prev_failure))
        self.stalled = self.stalled + 1 if same else 0
        self._prev = situation
        self._prev_failure = None if succeeded else failure
        prev = self._last_visit.get(situation)
        self._last_visit[situation] = self._t
        if prev is None or self._last_exogenous > prev or self._last_success <= prev:
            return None
        clean = self._last_failure <= prev
        self.seen += 1
        self.cycles += clean
        self.failed_cycles += not clean
        return Cycle(self._t - prev, self.cycles, prev, self._t, clean)

    def forget(self, *, keep: Hashable | None = None, cycles: bool = False) -> None:
        """Forget the situations seen (after committing: only cycles made since count), except
        ``keep`` (the situation now); ``cycles`` also resets the count (after progress)."""
        self._last_visit.clear()
        if keep is not None:
            self._last_visit[keep] = self._t
        if cycles:
            self.cycles = 0
            self.failed_cycles = 0

    @property
    def livelocked(self) -> bool:
        return self.cycles >= self.max_cycles


def stall_reason(times: int, action: Action | None, obs: Observation) -> str:
    """Why a run that stood still was given up."""
    what = action.pddl() if action is not None else "the last action"
    why = obs.info.get("reason")
    return (f"stalled: {what} failed {times} times in a row and left the belief and the plan stack as "
            f"they were, or failed the same way each time{f' (last: {why})' if why else ''}; the world refuses "
            "it, or the belief is wrong and the world reports outcomes only")


def failed_cycles_reason(cyc: Cycle, times: int, failed: tuple[Action, Observation] | None) -> str:
    """Why a run whose failures kept bringing it back to situations seen before was given up
    (``failed``: the last action that failed, and what the world said)."""
    what = failed[0].pddl() if failed is not None else "unknown"
    why = failed[1].info.get("reason") if failed is not None else None
    return (f"no progress: {times} cycles since the last progress each had a failed action (the last: "
            f"{cyc.describe()}; last failure: {what}{f', {why}' if why else ''}); the failures recur in the "
            "same situations, so they are not chance: the plans made here do not account for what makes them fail")


def situation(belief_fp: Hashable, goals: Iterable[Hashable]) -> Hashable:
    """The fingerprint the detector compares: the belief's and the plan stack's goals."""
    return (belief_fp, tuple(goals))


class RepeatedActions:
    """A loop the fingerprints miss: the same sequence of ground actions, over and over.

    A belief that drifts on its own (a battery that drains on every flight, a position spread
    that grows) is never in the same situation twice, so :class:`CycleDetector` sees no cycle:
    a held-out drone flew between the depot and a parcel 266 times, every flight a success, until
    the time limit.  This watches the actions instead: the same block of ``2..max_period`` ground
    actions (not all one action: repeated looks that sharpen an estimate are progress) repeated
    ``repeats`` times in a row, every action a success with no exogenous change, while no more of
    the root goal's atoms held than before the block began.  At 4 repeats it ended two held-out
    ward runs (a shuttle through a door while the knowledge of another door decayed) that the
    world broke a few rounds later and that reached the goal; at 8 they reach it.  Blocks of up to
    ``max_period`` = 16 actions: a held-out mine's RCHPN (a particle belief, so no cycle counted past
    one) repeated a 14-action round of tow, gate, charge and moves until its 1,000-action budget.  A
    block longer than 8 actions needs only the repeats that make ``8 * repeats`` actions (at least 4):
    five rounds of 14 actions, not eight.
    """

    def __init__(self, repeats: int = 8, max_period: int = 16) -> None:
        if repeats < 2 or max_period < 2:
            raise ValueError("repeats and max_period must be >= 2")
        self.repeats, self.max_period = repeats, max_period
        self._history: list[Hashable] = []
        self._best = -1

    def needed(self, period: int) -> int:
        """The repeats that make a loop of blocks of ``period`` actions."""
        if period <= 8:
            return self.repeats
        return min(self.repeats, max(4, -(-8 * self.repeats // period)))

    def reset(self) -> None:
        """Forget the actions seen (a new way of planning begins)."""
        self._history.clear()

    def observe(self, action: Hashable, *, succeeded: bool, exogenous: bool, achieved: int) -> tuple[int, tuple[Hashable, ...]] | None:
        """After one more action (``achieved``: how many root goal atoms hold now); the repeated
        block's period and actions when the loop is complete, else None."""
        if not succeeded or exogenous or achieved > self._best:
            self._history.clear()
            self._best = max(self._best, achieved)
            if not succeeded or exogenous:
                return None
        h = self._history
        h.append(action)
        if len(h) > self.repeats * self.max_period:
            del h[0]
        for p in range(2, self.max_period + 1):
            n = self.needed(p)
            if len(h) < n * p:
                continue
            block = h[-p:]
            if len(set(block)) > 1 and all(h[-(k + 1) * p:len(h) - k * p] == block for k in range(1, n)):
                return p, tuple(block)
        return None


def repeated_actions_reason(period: int, block: tuple[Hashable, ...], repeats: int) -> str:
    """Why a run that kept repeating the same actions was given up."""
    names = ", ".join(str(a) for a in block[:4]) + (", …" if len(block) > 4 else "")
    return (f"livelock: the same {period} actions ({names}) repeated {repeats} times in a row, each a success "
            "with no exogenous change, and no more goal atoms hold than before; the belief's fingerprint "
            "did not repeat (it drifts), so no cycle was seen")
