"""The online policy keeps the plan it has when a replanning search runs out of nodes (issue 14)."""

from __future__ import annotations

from typing import Any

from nowplan.acting.metrics import Outcome
from nowplan.acting.online import INCUMBENT_FACTOR, INCUMBENT_MIN_NODES, OnlinePolicy
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.registry import get_domain
from nowplan.planning.plan import PlanResult, PlanStatus
from nowplan.trace import Trace


class _RunsOut(OnlinePolicy):
    """Plans once; every later search (capped or not) runs out of nodes."""

    calls: list[bool]

    def _plan(self, prev: Any, deadline: float, capped: bool = True) -> PlanResult:
        self.calls.append(capped and self.incumbent_budget() is not None)
        if len(self.calls) == 1:
            return super()._plan(prev, deadline, capped)
        return PlanResult(PlanStatus.NODE_LIMIT, reason="expanded 7 nodes without a plan")


def _policy(cls: type[OnlinePolicy], failure: float = 0.0) -> OnlinePolicy:
    ep = get_domain("logistics").scenario("tiny")(0)
    if failure:
        ep.world.set_faults(failure_prob=failure)
    return cls(ep.problem, ep.world, ep.belief, parse_strategy("online", time_limit=30.0), trace=Trace())


def test_a_replanning_search_that_runs_out_keeps_the_plan() -> None:
    p = _policy(_RunsOut)
    assert isinstance(p, _RunsOut)
    p.calls = []
    m = p.run()
    # one plan; the second call (capped: the plan's rest applies) ran out, and the rest was followed
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.plans_made == 1 and m.plan_failures == 1 and p.calls[:2] == [False, True]
    notes = [e["text"] for e in p.trace.events if e.get("event") == "note"]
    assert any("committing to its" in n for n in notes), notes


def test_a_kept_plan_whose_next_step_does_not_apply_is_not_followed() -> None:
    p = _policy(OnlinePolicy)
    res = p._plan(None, 1e9)
    assert res.plan is not None and len(res.plan.actions) >= 2
    acts = list(res.plan.actions)
    ran_out = PlanResult(PlanStatus.NODE_LIMIT, reason="expanded 7 nodes without a plan")
    # a step that needs an earlier one taken first does not apply yet
    late = next(i for i, a in enumerate(acts) if not all(p.domain.holds(x, p.belief) for x in a.preconditions(None)))
    p._rest = acts[late:]
    assert not p._fall_back(ran_out) and p._tail == [] and p._rest == []
    p._rest = acts  # from the start it applies
    assert p._fall_back(ran_out) and p._tail == acts
    p._rest = acts  # a search that proved the goal unreachable is not overruled
    assert not p._fall_back(PlanResult(PlanStatus.UNSOLVABLE, reason="search space exhausted"))


def test_the_incumbent_budget_scales_with_the_search_that_made_the_plan() -> None:
    p = _policy(OnlinePolicy)
    p._rest = list(p._plan(None, 1e9).plan.actions)  # type: ignore[union-attr]
    p._rest_expanded = 10
    assert p.incumbent_budget() == INCUMBENT_MIN_NODES
    p._rest_expanded = 300
    assert p.incumbent_budget() == INCUMBENT_FACTOR * 300
    p._rest_expanded = 10**6  # past the planner's own budget: no cap
    assert p.incumbent_budget() is None
