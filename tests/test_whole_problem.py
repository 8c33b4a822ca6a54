"""Whole-problem planning in two passes (nowplan.acting.whole), with a stand-in planner and beliefs."""

from __future__ import annotations

import random
from typing import Any

from nowplan.acting.whole import WIDE_SHARE, plan_whole_problem
from nowplan.core.atoms import Goal
from nowplan.core.levels import flat_levels
from nowplan.domains.registry import get_domain
from nowplan.planning.config import PlannerConfig
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import PlanResult, PlanStatus


class _Guarded:
    def planning_gave_up(self, context: Any) -> str | None:
        return None


class _Planner:
    """Solves only in the restricted pass (or never): records the budgets and contexts it was given."""

    def __init__(self, solves_when_restricted: bool = True, first: PlanStatus = PlanStatus.NODE_LIMIT) -> None:
        self.calls: list[tuple[int, bool]] = []
        self.solves = solves_when_restricted
        self.first = first

    def __call__(self, domain: Any, objects: Any, belief: Any, goal: Goal, levels: Any, config: PlannerConfig,
                 context: PlanningContext, rng: random.Random) -> PlanResult:
        self.calls.append((config.max_nodes, context.restricted))
        if context.restricted and self.solves:
            return PlanResult(PlanStatus.SOLVED, None, "", expanded=30, cpu_time_s=0.5)
        status = self.first if not context.restricted else PlanStatus.NODE_LIMIT
        return PlanResult(status, None, f"expanded {config.max_nodes} nodes without a plan",
                          expanded=config.max_nodes, cpu_time_s=1.0)


def _call(planner: _Planner, belief: Any, ctx: PlanningContext | None = None) -> PlanResult:
    domain = get_domain("logistics").scenario("tiny")(0).problem.domain
    return plan_whole_problem(planner, domain, {}, belief, Goal(()), flat_levels(), PlannerConfig(max_nodes=50_000),
                              ctx or PlanningContext((), {"whole_problem": True}), random.Random(0))


def test_an_unrestricted_pass_first_then_the_restricted_one_with_the_whole_budget() -> None:
    p = _Planner()
    res = _call(p, _Guarded())
    assert p.calls == [(int(50_000 * WIDE_SHARE), False), (50_000, True)]
    assert res.solved and res.expanded == int(50_000 * WIDE_SHARE) + 30 and res.cpu_time_s == 1.5
    assert any("unrestricted pass" in a for a in res.attempts)


def test_no_second_pass_after_a_proof_or_a_time_limit_nor_without_a_guard() -> None:
    for status in (PlanStatus.UNSOLVABLE, PlanStatus.TIME_LIMIT):
        p = _Planner(first=status)
        assert _call(p, _Guarded()).status is status and len(p.calls) == 1
    p = _Planner()
    assert _call(p, object()).status is PlanStatus.NODE_LIMIT and p.calls == [(50_000, False)]  # one call, as before
    p = _Planner()
    _call(p, _Guarded(), PlanningContext((), {"whole_problem": True, "restricted": True}))
    assert p.calls == [(50_000, True)]


def test_both_passes_failing_report_the_restricted_pass() -> None:
    p = _Planner(solves_when_restricted=False)
    res = _call(p, _Guarded())
    assert res.status is PlanStatus.NODE_LIMIT and "50000" in res.reason and len(p.calls) == 2


class _Reporting(_Guarded):
    """A guarded belief whose generators gave up on every call (or never)."""

    def __init__(self, gave_up: bool) -> None:
        self.gave_up = gave_up
        self.asked: list[PlanningContext] = []

    def generators_gave_up(self, context: Any) -> str | None:
        self.asked.append(context)
        return "its move generator gave up after 1500 move requests" if self.gave_up else None


class _Exhausts(_Planner):
    """The restricted pass exhausts its search space."""

    def __call__(self, domain: Any, objects: Any, belief: Any, goal: Goal, levels: Any, config: PlannerConfig,
                 context: PlanningContext, rng: random.Random) -> PlanResult:
        if context.restricted:
            self.calls.append((config.max_nodes, True))
            return PlanResult(PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan at this level",
                              expanded=1_000, cpu_time_s=1.0)
        return super().__call__(domain, objects, belief, goal, levels, config, context, rng)


def test_a_restricted_pass_exhausted_after_its_generators_gave_up_is_no_proof() -> None:
    """The restricted pass searches on without new moves once the generator gave up: its exhausted
    space ends the call as a budget, with both reasons, not as 'unsolvable' (NAMO sigma 0.2, online)."""
    belief = _Reporting(gave_up=True)
    res = _call(_Exhausts(), belief)
    assert res.status is PlanStatus.NODE_LIMIT
    assert "search space exhausted" in res.reason and "gave up after 1500 move requests" in res.reason
    assert len(belief.asked) == 1 and belief.asked[0].restricted
    # a generator that did not give up: the exhausted space stands as a proof
    assert _call(_Exhausts(), _Reporting(gave_up=False)).status is PlanStatus.UNSOLVABLE
    assert _call(_Exhausts(), _Guarded()).status is PlanStatus.UNSOLVABLE  # a belief that does not report
