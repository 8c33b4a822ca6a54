"""Backtracking across abstraction levels when an abstract step cannot be refined (acting/backtrack.py)."""

from __future__ import annotations

import pytest

from nowplan.acting.backtrack import Nogoods
from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.registry import Episode
from nowplan.planning.context import PlanningContext
from nowplan.planning.regression import plan
from nowplan.trace import Trace
from nowplan.worlds.symbolic import SymbolicWorld

P = Precondition


def _domain(with_long_way: bool) -> Domain:
    """Two ways in: the short one needs a key nobody can make, which only its refinement sees.

    ``go_short`` hides its ``key`` precondition (criticality 1) below the top
    level, and its subgoal ``there & short`` can only be reached through it,
    so the abstract plan ``go_short, enter_short`` (cost 2) has no refinement
    (``make_key`` needs a forge);
    ``go_long, enter_long`` (cost 15) has.
    """
    preds = {n: Predicate(n, 0) for n in ("start", "forge", "key", "there", "short", "inside")}
    ops = [
        # the key can be made only at a forge, and there is none (not a static fact: make_key adds it)
        Operator("make_key", (), (P(atom("forge"), 1),), (atom("key"),), cost=1.0),
        Operator("go_short", (), (P(atom("start"), 2), P(atom("key"), 1)), (atom("there"), atom("short")), cost=1.0),
        Operator("enter_short", (), (P(atom("there"), 2), P(atom("short"), 2)), (atom("inside"),), cost=1.0),
    ]
    if with_long_way:
        ops += [
            Operator("go_long", (), (P(atom("start"), 2),), (atom("there"),), cost=5.0),
            Operator("enter_long", (), (P(atom("there"), 2),), (atom("inside"),), cost=10.0),
        ]
    return Domain("doors", preds, tuple(ops))


def _episode(with_long_way: bool) -> Episode:
    dom = _domain(with_long_way)
    init = State([atom("start")])
    problem = Problem(dom, {}, SymbolicBelief(init), Goal.of([atom("inside")], dom.rules), "doors")
    return Episode(problem, SymbolicWorld(dom, init, seed=0), SymbolicBelief(init), "doors")


@pytest.mark.parametrize("strategy", ["hpn", "hpn+flexible", "hpn+aggressive", "hpn+selective"])
def test_an_abstract_step_without_refinement_is_replanned_at_the_level_above(strategy):
    ep = _episode(with_long_way=True)
    top = plan(ep.problem.domain, {}, ep.belief, ep.problem.goal, LevelMap(ep.problem.domain.top_level))
    assert top.plan is not None and [a.name for a in top.plan.actions] == ["go_short", "enter_short"]
    tr = Trace()
    m = run_episode(ep, parse_strategy(strategy), seed=0, trace=tr)
    assert m.outcome is Outcome.REACHED, m.reason
    assert dict(m.action_counts) == {"go_long": 1, "enter_long": 1}
    notes = [e["text"] for e in tr.of("note") if e["text"].startswith("backtrack")]
    assert notes and "go_short" in notes[0]


def test_with_no_other_way_the_run_ends_with_the_planners_reason_not_a_loop():
    tr = Trace()
    m = run_episode(_episode(with_long_way=False), parse_strategy("hpn"), seed=0, trace=tr)
    assert m.outcome is Outcome.FAILED
    assert m.reason.startswith("no plan for the goal") and m.actions == 0
    assert len(tr.of("plan_failed")) <= 3  # the refinement, then the root with the nogood


def test_a_forbidden_first_step_is_not_the_start_of_a_plan_but_may_come_later():
    dom = _domain(with_long_way=True)
    b = State([atom("start")])
    goal = Goal.of([atom("inside")], dom.rules)
    first = plan(dom, {}, b, goal, flat_levels())
    assert first.plan is None or first.plan.actions[0].name != "go_short"  # key: not at the concrete level
    top = LevelMap(dom.top_level)
    free = plan(dom, {}, b, goal, top)
    assert free.plan is not None and free.plan.actions[0].name == "go_short"
    ctx = PlanningContext((), {"forbidden_first": frozenset({free.plan.actions[0].key})})
    other = plan(dom, {}, b, goal, top, context=ctx)
    assert other.plan is not None and [a.name for a in other.plan.actions] == ["go_long", "enter_long"]
    # forbidding enter_long as a first step changes nothing: it is not a first step here
    ctx2 = PlanningContext((), {"forbidden_first": frozenset({other.plan.actions[1].key})})
    again = plan(dom, {}, b, goal, top, context=ctx2)
    assert again.plan is not None and again.plan.actions == free.plan.actions


def test_nogoods_are_per_goal_and_level_and_cleared():
    n = Nogoods()
    g, h = Goal.of([atom("inside")]), Goal.of([atom("there")])
    n.learn(g, LevelMap(2), ("go_short", ()))
    assert n.forbidden(g, LevelMap(2)) == {("go_short", ())}
    assert not n.forbidden(g, LevelMap(1)) and not n.forbidden(h, LevelMap(2))
    n.clear()
    assert len(n) == 0 and not n.forbidden(g, LevelMap(2))
