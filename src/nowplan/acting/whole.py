"""A planning call for the whole problem: two searches interleaved when the domain's generators guard
against loops.

A refinement (a call below the top of a hierarchical plan) that a domain's generator gives up on
fails, and the level above plans again.  A call for the whole problem (a flat strategy, the online
policy) has no level above, and the same guard decides *which plans it can find*: NAMO's move
generator offers moves for its first 1,500 requests only (``LOOP_LIMIT``), about one per node
expanded, so a search that needs a move later is starved (issue 14: ``flat`` on
``domain1?sigma_per_m=0.1`` seed 16, 50,000 nodes without a plan), while without the guard another
search is lost among moves and expands its 50,000 nodes without a plan where the guarded one finds
one in about 20,000 (``online``, seed 4; ``online`` on ``sigma_per_m=0.08`` seed 5).

So a whole-problem call runs two searches, one with the generators unrestricted (they offer moves up
to the search's own node budget) and one with them restricted (``PlanningContext.restricted``), in
alternating slices: each runs until the regression search next polls the belief's
``planning_gave_up`` (every :data:`POLL_EVERY` expansions), then waits while the other runs its
slice, the unrestricted one first in every round.  The call ends when either finds a plan (a plan
found in the unrestricted search's slice is taken before the restricted search runs that round), when
the unrestricted search ends without one for a reason other than its node budget (then the restricted
one, which is offered fewer moves, cannot do better), when both have ended, or when the two together
have expanded the call's ``max_nodes``.  Neither search gets a fixed share of the budget: each gets
what the other leaves, and a search that ends early leaves the rest to the other.

The searches run in two threads of which exactly one runs at any time (each hands over at its polls
and waits for its turn), so the call is as deterministic as one search: the same slices in the same
order, whatever the machine's load.  The pause is made at the poll by giving the belief, for the
duration of the call, an instance attribute ``planning_gave_up`` that takes turns before asking the
belief's own method.  A belief that takes no instance attributes (``__slots__``, frozen) gets the two
searches one after the other, each with half the budget.  Beliefs without such a guard
(:class:`~nowplan.belief.protocols.GivesUp`) get one call as before.
"""

from __future__ import annotations

import logging
import random
import threading
import time
from collections.abc import Callable, Mapping
from dataclasses import replace
from typing import Any

from nowplan.belief.protocols import GivesUp
from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.planning.config import PlannerConfig
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import PlanResult, PlanStatus

log = logging.getLogger(__name__)

# How many nodes the regression search expands between two polls of ``planning_gave_up``
# (planning/regression_search.py: ``not exp & 63``): one slice, and the unit the two searches' joint
# node count is kept in (tests/test_whole_problem.py checks it against the search).
POLL_EVERY = 64

Planner = Callable[..., PlanResult]
WIDE, NARROW = 0, 1
_NAMES = ("unrestricted", "restricted")


class _Turns:
    """Two searches taking turns, one slice each, until the call is decided (see the module docstring)."""

    def __init__(self, max_nodes: int) -> None:
        self.max_nodes = max_nodes
        self.cond = threading.Condition()
        self.turn = WIDE
        self.polls = [0, 0]
        self.finished = [False, False]
        self.results: list[PlanResult | None] = [None, None]
        self.errors: list[BaseException | None] = [None, None]
        self.stop: list[str | None] = [None, None]  # why a search ends at its next poll (or before it starts)
        self.threads: dict[int, int] = {}  # thread ident -> search

    def counted(self) -> int:
        """Nodes expanded so far by both: a finished search's own count, a running one's polls."""
        n = 0
        for i in (WIDE, NARROW):
            res = self.results[i]
            n += res.expanded if res is not None else self.polls[i] * POLL_EVERY
        return n

    def _why(self, i: int) -> str | None:
        if self.stop[i] is not None:
            return self.stop[i]
        n = self.counted()
        if n >= self.max_nodes:
            return (f"expanded {n} nodes without a plan (the unrestricted and restricted searches together, "
                    f"max_nodes {self.max_nodes})")
        return None

    def _wait_turn(self, i: int) -> None:
        while self.turn != i and self.stop[i] is None:
            self.cond.wait()

    def poll(self, i: int) -> str | None:
        """Search ``i`` polls after a slice: hand over to the other; why it must end, or None."""
        with self.cond:
            self.polls[i] += 1
            why = self._why(i)
            if why is None and not self.finished[1 - i]:
                self.turn = 1 - i
                self.cond.notify_all()
                self._wait_turn(i)
                why = self._why(i)
            return why

    def start(self, i: int) -> bool:
        """Wait for search ``i``'s first turn: False if the call was decided before it."""
        with self.cond:
            self._wait_turn(i)
            return self.stop[i] is None

    def finish(self, i: int, result: PlanResult | None, error: BaseException | None) -> None:
        with self.cond:
            self.results[i], self.errors[i], self.finished[i] = result, error, True
            other = 1 - i
            if error is not None:
                self.stop[other] = f"the {_NAMES[i]} search raised {type(error).__name__}"
            elif result is not None and result.solved:
                self.stop[other] = f"the {_NAMES[i]} search found a plan"
            elif i == WIDE and result is not None and result.status is not PlanStatus.NODE_LIMIT:
                self.stop[other] = f"the unrestricted search ended: {result.status.value}"
            self.turn = other
            self.cond.notify_all()

    def abort(self, why: str) -> None:
        with self.cond:
            for i in (WIDE, NARROW):
                self.stop[i] = self.stop[i] or why
            self.cond.notify_all()

    def done(self) -> bool:
        return all(self.finished)


def plan_whole_problem(
    planner: Planner, domain: Domain, objects: Mapping[str, str | None], belief: Any, goal: Goal,
    levels: LevelMap, config: PlannerConfig, context: PlanningContext, rng: random.Random,
) -> PlanResult:
    """Plan ``goal`` with ``planner`` (regression's signature): unrestricted and restricted searches
    interleaved, within ``config.max_nodes`` together (see the module docstring)."""
    if not isinstance(belief, GivesUp) or context.restricted:
        return planner(domain, objects, belief, goal, levels, config, context, rng)
    contexts = (context, replace(context, extras={**context.extras, "restricted": True}))
    turns = _Turns(config.max_nodes)
    own = belief.planning_gave_up
    hooked: Any = belief  # (the GivesUp protocol's method is replaced on this instance only)

    def polled(ctx: Any) -> str | None:
        i = turns.threads.get(threading.get_ident())
        why = turns.poll(i) if i is not None else None
        return why if why is not None else own(ctx)

    try:
        prior = vars(hooked).get("planning_gave_up")  # an instance attribute of its own, put back after
        hooked.planning_gave_up = polled
    except (AttributeError, TypeError):  # __slots__ or frozen: no pause point, so one search after the other
        return _one_after_the_other(planner, domain, objects, belief, goal, levels, config, contexts, rng)

    def search(i: int) -> None:
        turns.threads[threading.get_ident()] = i
        result: PlanResult | None = None
        try:
            if turns.start(i):
                result = planner(domain, objects, belief, goal, levels, config, contexts[i], rng)
        except BaseException as exc:  # noqa: BLE001 - handed to the caller's thread below
            turns.finish(i, None, exc)
        else:
            turns.finish(i, result, None)

    t_cpu = time.process_time()
    threads = [threading.Thread(target=search, args=(i,), name=f"nowplan-{_NAMES[i]}", daemon=True)
               for i in (WIDE, NARROW)]
    try:
        for t in threads:
            t.start()
        with turns.cond:
            while not turns.done():
                turns.cond.wait()
    finally:
        if not turns.done():  # interrupted (e.g. KeyboardInterrupt): end both searches at their next poll
            turns.abort("the planning call was interrupted")
        for t in threads:
            if t.ident is not None:
                t.join()
        if prior is None:
            del hooked.planning_gave_up
        else:
            hooked.planning_gave_up = prior
    for err in turns.errors:
        if err is not None:
            raise err
    return _combine(turns.results[WIDE], turns.results[NARROW], time.process_time() - t_cpu)


def _combine(wide: PlanResult | None, narrow: PlanResult | None, cpu: float) -> PlanResult:
    """The call's result: the plan found (the unrestricted one first), else why both failed."""
    assert wide is not None  # the unrestricted search always starts
    if wide.solved or narrow is None or (wide.status is not PlanStatus.NODE_LIMIT and not narrow.solved):
        best, note = wide, () if narrow is None else (f"restricted search: {narrow.reason or narrow.status.value}",)
        attempts = (*wide.attempts, *note)
    else:
        best = narrow
        attempts = (f"unrestricted search: {wide.reason}", *narrow.attempts)
    log.info("whole-problem call: unrestricted %s after %d nodes, restricted %s after %d nodes; %.2f CPU s",
             wide.status.value, wide.expanded, "-" if narrow is None else narrow.status.value,
             0 if narrow is None else narrow.expanded, cpu)
    spent = wide.expanded + (narrow.expanded if narrow is not None else 0)
    generated = wide.generated + (narrow.generated if narrow is not None else 0)
    return replace(best, cpu_time_s=cpu, expanded=spent, generated=generated, attempts=attempts)


def _one_after_the_other(
    planner: Planner, domain: Domain, objects: Mapping[str, str | None], belief: Any, goal: Goal,
    levels: LevelMap, config: PlannerConfig, contexts: tuple[PlanningContext, PlanningContext],
    rng: random.Random,
) -> PlanResult:
    log.info("belief %s takes no instance attributes: its whole-problem searches run one after the other",
             type(belief).__name__)
    half = max(1, config.max_nodes // 2)
    t_cpu = time.process_time()
    cfg = replace(config, max_nodes=half, shortcut_nodes=min(config.shortcut_nodes, half))
    wide = planner(domain, objects, belief, goal, levels, cfg, contexts[WIDE], rng)
    narrow = None
    if not wide.solved and wide.status is PlanStatus.NODE_LIMIT:
        rest = max(1, config.max_nodes - wide.expanded)
        cfg = replace(config, max_nodes=rest, shortcut_nodes=min(config.shortcut_nodes, rest))
        narrow = planner(domain, objects, belief, goal, levels, cfg, contexts[NARROW], rng)
    return _combine(wide, narrow, time.process_time() - t_cpu)
