"""An operator parameter the planner can only bind from objects, and a belief that holds a value
there that is no object: "no plan" names the operator, the parameter and the fixes
(held-out greenhouse, benchmarks/results/heldout12: take(r, t, q) with lies(t, q) holding a pose)."""

from __future__ import annotations

import logging

import pytest

from nowplan.api import (
    Domain, Episode, Generator, Goal, Operator, Outcome, Precondition, Predicate, Problem, State, SymbolicBelief,
    SymbolicWorld, Var, atom, parse_strategy, run_episode,
)
from nowplan.core.unbound import unbindable_parameters

t, q = Var("t"), Var("q")


def _domain(generator: bool, tested: bool = True) -> Domain:
    def where(bindings: object, goal: object, belief: object, context: object) -> object:
        tool = bindings.get(t)  # type: ignore[attr-defined]
        return ({q: s} for (x, s) in belief.facts("lies") if x == tool)  # type: ignore[attr-defined]

    gens = (Generator("where", (q,), where, (t,)),) if generator else ()
    preds = {p.name: p for p in (Predicate("lies", 2, ("tool", None)), Predicate("holding", 1, ("tool",)))}
    if tested:  # (a tested predicate, as the greenhouse's: its planner grounds call by call)
        preds["sunny"] = Predicate("sunny", 0, test=lambda belief, args, value: bool(value))
    take = Operator("take", (t, q), (Precondition(atom("lies", t, q), 1),),
                    (atom("holding", t), atom("lies", t, q, value=False)), param_types=("tool", None),
                    generators=gens)
    return Domain("shed", preds, (take,), types={"tool": None})


def _episode(generator: bool, pose_is_object: bool, tested: bool = True) -> Episode:
    dom = _domain(generator, tested)
    init = State([atom("lies", "sprayer", "0.0,2.0")])
    objects = {"sprayer": "tool", **({"0.0,2.0": None} if pose_is_object else {})}
    prob = Problem(dom, objects, SymbolicBelief(init), Goal.of([atom("holding", "sprayer")], dom.rules), "shed")
    return Episode(prob, SymbolicWorld(dom, init), prob.init, "shed")


@pytest.mark.parametrize("strategy", ["hpn", "flat", "online"])
def test_no_plan_names_the_parameter_no_object_can_bind(strategy: str, caplog: pytest.LogCaptureFixture) -> None:
    with caplog.at_level(logging.WARNING):
        m = run_episode(_episode(False, False), parse_strategy(strategy, max_actions=20, time_limit=10), seed=0)
    assert m.outcome is Outcome.FAILED
    assert "operator take: parameter ?q" in m.reason and "'0.0,2.0' is no object" in m.reason, m.reason
    assert "Generator" in m.reason and "Problem(objects=" in m.reason
    assert "operator take: parameter ?q" in caplog.text  # said at the start too


@pytest.mark.parametrize("generator, pose_is_object, tested", [(True, False, True), (False, True, True),
                                                               (False, False, False)])
def test_either_fix_plans_and_says_nothing(generator: bool, pose_is_object: bool, tested: bool) -> None:
    """A generator, the value as an object, or a domain ground from its facts (no tests): a plan, no hint."""
    ep = _episode(generator, pose_is_object, tested)
    assert unbindable_parameters(ep.problem.domain, ep.problem.all_objects, ep.belief) is None
    m = run_episode(ep, parse_strategy("hpn", max_actions=20, time_limit=10), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason


def test_a_parameter_an_effect_makes_true_is_bound_from_the_goal() -> None:
    """``put(t, q)`` needs ``free(q)`` and makes ``lies(t, q)``: the goal ``lies(sprayer, "0.0,2.0")`` binds
    ``q`` through the effect, so a pose in ``free`` is no reason for a hint, and the plan is found."""
    preds = {p.name: p for p in (Predicate("lies", 2, ("tool", None)), Predicate("holding", 1, ("tool",)),
                                 Predicate("free", 1, (None,)),
                                 Predicate("sunny", 0, test=lambda belief, args, value: bool(value)))}
    put = Operator("put", (t, q), (Precondition(atom("holding", t), 1), Precondition(atom("free", q), 1)),
                   (atom("lies", t, q), atom("free", q, value=False), atom("holding", t, value=False)),
                   param_types=("tool", None))
    dom = Domain("shed", preds, (put,), types={"tool": None})
    init = State([atom("holding", "sprayer"), atom("free", "0.0,2.0")])
    prob = Problem(dom, {"sprayer": "tool"}, SymbolicBelief(init),
                   Goal.of([atom("lies", "sprayer", "0.0,2.0")], dom.rules), "shed")
    assert unbindable_parameters(dom, prob.all_objects, prob.init) is None
    ep = Episode(prob, SymbolicWorld(dom, init), prob.init, "shed")
    m = run_episode(ep, parse_strategy("hpn", max_actions=20, time_limit=10), seed=0)
    assert m.outcome is Outcome.REACHED, m.reason
