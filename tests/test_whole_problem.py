"""Whole-problem planning (nowplan.acting.whole): the unrestricted and restricted searches interleaved,
with stand-in planners that poll the belief as the regression search does, and with the real one."""

from __future__ import annotations

import random
import threading
from typing import Any

import pytest

from nowplan.acting.whole import POLL_EVERY, plan_whole_problem
from nowplan.belief.protocols import GivesUp
from nowplan.core.atoms import Goal
from nowplan.core.levels import flat_levels
from nowplan.domains.registry import get_domain
from nowplan.planning.config import PlannerConfig
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import PlanResult, PlanStatus

WHOLE = PlanningContext((), {"whole_problem": True})


class _Guarded:
    """A belief whose generators guard against loops (GivesUp); records the polls it answers itself."""

    def __init__(self) -> None:
        self.asked: list[bool] = []

    def planning_gave_up(self, context: Any) -> str | None:
        self.asked.append(context.restricted)
        return None


class _Slotted:
    __slots__ = ()

    def planning_gave_up(self, context: Any) -> str | None:
        return None


class _Planner:
    """Expands POLL_EVERY nodes per poll of ``belief.planning_gave_up``, as the regression search does;
    the unrestricted search ends after ``wide`` polls with ``wide_status``, the restricted after ``narrow``
    (None: never by itself).  Records which search ran each slice, in order."""

    def __init__(self, wide: int | None, narrow: int | None, wide_status: PlanStatus = PlanStatus.SOLVED,
                 narrow_status: PlanStatus = PlanStatus.SOLVED) -> None:
        self.ends = {False: (wide, wide_status), True: (narrow, narrow_status)}
        self.slices: list[str] = []
        self.configs: list[PlannerConfig] = []

    def __call__(self, domain: Any, objects: Any, belief: Any, goal: Goal, levels: Any, config: PlannerConfig,
                 context: PlanningContext, rng: random.Random) -> PlanResult:
        self.configs.append(config)
        end, status = self.ends[context.restricted]
        polls = 0
        while True:
            self.slices.append("N" if context.restricted else "W")
            if end is not None and polls == end:
                return PlanResult(status, None, "" if status is PlanStatus.SOLVED else status.value,
                                  expanded=polls * POLL_EVERY, generated=2 * polls * POLL_EVERY)
            polls += 1
            if polls * POLL_EVERY > config.max_nodes:
                return PlanResult(PlanStatus.NODE_LIMIT, None, f"expanded {config.max_nodes} nodes without a plan",
                                  expanded=config.max_nodes)
            why = belief.planning_gave_up(context) if isinstance(belief, GivesUp) else None
            if why is not None:
                return PlanResult(PlanStatus.NODE_LIMIT, None, why, expanded=polls * POLL_EVERY)


def _call(planner: Any, belief: Any, ctx: PlanningContext = WHOLE, max_nodes: int = 50 * POLL_EVERY) -> PlanResult:
    domain = get_domain("logistics").scenario("tiny")(0).problem.domain
    return plan_whole_problem(planner, domain, {}, belief, Goal(()), flat_levels(), PlannerConfig(max_nodes=max_nodes),
                              ctx, random.Random(0))


def test_the_two_searches_alternate_slices_and_the_first_plan_ends_the_call() -> None:
    p, b = _Planner(wide=None, narrow=3), _Guarded()
    res = _call(p, b)
    # a slice each, the unrestricted first; the restricted finds its plan in its fourth slice
    assert p.slices == ["W", "N", "W", "N", "W", "N", "W", "N"]
    # expansions of both (the unrestricted search's 4 slices, the restricted search's 3), generated of both
    assert res.solved and res.expanded == 7 * POLL_EVERY and res.generated == 6 * POLL_EVERY
    assert any(a.startswith("unrestricted search: the restricted search found a plan") for a in res.attempts)
    assert b.asked == [False, True, False, True, False, True]  # the belief's own check, after each turn
    assert "planning_gave_up" not in vars(b)  # the pause point is removed after the call
    # each search was given the whole budget: the joint count bounds them
    assert [c.max_nodes for c in p.configs] == [50 * POLL_EVERY] * 2


def test_a_plan_found_in_the_unrestricted_slice_is_taken_before_the_restricted_slice_of_that_round() -> None:
    p = _Planner(wide=3, narrow=3)
    res = _call(p, _Guarded())
    assert p.slices == ["W", "N", "W", "N", "W", "N", "W"]  # the restricted search's fourth slice never runs
    assert res.solved and res.expanded == 6 * POLL_EVERY
    assert any(a.startswith("restricted search: the unrestricted search found a plan") for a in res.attempts)


def test_neither_search_is_starved_and_together_they_keep_the_node_budget() -> None:
    # the unrestricted search needs 40 slices: more than a fixed 20 % share (10 of 50) would give it
    p = _Planner(wide=40, narrow=None)
    assert _call(p, _Guarded(), max_nodes=100 * POLL_EVERY).solved
    # neither ends: the call stops once both have expanded max_nodes together
    p = _Planner(wide=None, narrow=None)
    res = _call(p, _Guarded(), max_nodes=50 * POLL_EVERY)
    assert res.status is PlanStatus.NODE_LIMIT and "together" in res.reason and "max_nodes 3200" in res.reason
    assert 50 * POLL_EVERY <= res.expanded <= 51 * POLL_EVERY
    assert p.slices.count("W") == p.slices.count("N")


def test_a_search_that_ends_early_leaves_the_rest_of_the_budget_to_the_other() -> None:
    # the restricted search fails at once: the unrestricted one goes on alone, past half the budget
    p = _Planner(wide=40, narrow=2, narrow_status=PlanStatus.UNSOLVABLE)
    res = _call(p, _Guarded(), max_nodes=50 * POLL_EVERY)
    assert res.solved and p.slices[:6] == ["W", "N", "W", "N", "W", "N"] and set(p.slices[6:]) == {"W"}


@pytest.mark.parametrize("status", [PlanStatus.UNSOLVABLE, PlanStatus.TIME_LIMIT])
def test_an_unrestricted_search_ending_without_its_budget_ends_the_call(status: PlanStatus) -> None:
    # offered fewer moves, the restricted search cannot do better than a proof or a time limit
    p = _Planner(wide=2, narrow=None, wide_status=status)
    res = _call(p, _Guarded())
    assert res.status is status and p.slices == ["W", "N", "W", "N", "W"]


def test_one_call_without_a_guard_or_in_a_restricted_context() -> None:
    p = _Planner(wide=None, narrow=None)
    assert _call(p, object()).status is PlanStatus.NODE_LIMIT and len(p.configs) == 1  # cannot poll: one search
    p = _Planner(wide=None, narrow=1)
    assert _call(p, _Guarded(), PlanningContext((), {"whole_problem": True, "restricted": True})).solved
    assert len(p.configs) == 1


def test_a_belief_without_instance_attributes_gets_one_search_after_the_other() -> None:
    p = _Planner(wide=None, narrow=None)
    res = _call(p, _Slotted(), max_nodes=50 * POLL_EVERY)
    assert [c.max_nodes for c in p.configs] == [25 * POLL_EVERY, 25 * POLL_EVERY]
    assert res.status is PlanStatus.NODE_LIMIT


def test_an_error_in_a_search_reaches_the_caller_and_stops_the_other() -> None:
    class Boom(RuntimeError):
        pass

    def planner(*args: Any) -> PlanResult:
        ctx, belief = args[6], args[2]
        if ctx.restricted:
            raise Boom("restricted")
        while belief.planning_gave_up(ctx) is None:
            pass
        return PlanResult(PlanStatus.NODE_LIMIT, None, "stopped")

    b = _Guarded()
    with pytest.raises(Boom):
        _call(planner, b)
    assert "planning_gave_up" not in vars(b)
    assert not [t for t in threading.enumerate() if t.name.startswith("nowplan-")]


def test_with_the_regression_planner_on_namo_the_pause_point_is_polled_and_bounds_the_call() -> None:
    # the real search must poll the belief's planning_gave_up every POLL_EVERY expansions through the
    # instance (the interleaving's pause point): a budget too small for a plan is kept by both together
    from nowplan.planning.regression import plan as regression_plan

    spec = get_domain("namo")
    ep = spec.scenario("domain1")(3)  # its whole-problem call expands 256 nodes for a plan
    b = ep.belief
    res = plan_whole_problem(regression_plan, ep.problem.domain, ep.problem.objects, b, ep.problem.goal,
                             flat_levels(), PlannerConfig(max_nodes=2 * POLL_EVERY, time_limit=60.0), WHOLE,
                             random.Random(0))
    assert res.status is PlanStatus.NODE_LIMIT and "together" in res.reason, res.reason
    # each search stops within a slice past the joint bound (and at most once more per later attempt)
    assert 2 * POLL_EVERY <= res.expanded <= 2 * POLL_EVERY + 6 * POLL_EVERY
    assert "planning_gave_up" not in vars(b)
    # and the same call again gives the same search (the turns do not depend on the machine)
    again = plan_whole_problem(regression_plan, ep.problem.domain, ep.problem.objects, b, ep.problem.goal,
                               flat_levels(), PlannerConfig(max_nodes=2 * POLL_EVERY, time_limit=60.0), WHOLE,
                               random.Random(0))
    assert (again.expanded, again.generated, again.attempts) == (res.expanded, res.generated, res.attempts)
