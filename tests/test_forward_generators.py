"""Forward search with generators that read nothing of the goal (planning/forward_generators.py).

The forward task keeps a binding of an operator with generators only where the regression grounder
could make it: some effect, unified with a target, binds the outputs it names and the generators
propose the rest.  A generator whose values are not objects of the problem sends the call to the
regression search.  Found on the held-out tidy house: flat planning ran out of 10 s with a
``reads_nothing`` spot generator and took 0.07 s without it.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

import pytest

from nowplan.api import (
    Domain, Generator, Goal, Operator, PlannerConfig, PlanStatus, Precondition, Predicate, State, Var, atom,
    flat_levels, plan, reads_nothing,
)
from nowplan.errors import UsageError
from nowplan.planning.forward_generators import GeneratorFilter, NotEnumerable, generators_unsupported

T, U, D = Var("t"), Var("u"), Var("d")
SPOTS = ["s1", "s2", "s3"]


def _believed_spot(bindings: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
    """Where the belief says the thing is (the generator reads the belief, not the goal)."""
    for (t, u) in sorted(belief.facts("at")):
        if t == bindings.get(T):
            yield {U: u}


def _domain(gen: Generator) -> Domain:
    preds = {"at": Predicate("at", 2), "holding": Predicate("holding", 1), "seen": Predicate("seen", 1),
             "free": Predicate("free", 0)}
    fetch = Operator(  # no effect names u: the generator alone binds it
        "fetch", (T, U),
        (Precondition(atom("at", T, U)), Precondition(atom("free"))),
        (atom("holding", T), atom("free", value=False)),
        generators=(gen,),
    )
    look = Operator("look", (T, U), (Precondition(atom("at", T, U)),), (atom("seen", T),))
    return Domain("fetching", preds, (fetch, look))


def _objects() -> dict[str, str | None]:
    return {"cup": None, "book": None, **{s: None for s in SPOTS}}


STATE = State([atom("at", "cup", "s2"), atom("at", "book", "s3"), atom("free")])
GOAL = Goal.of([atom("holding", "cup"), atom("seen", "book")])


def _checked(res: Any, state: State, goal: Goal) -> list[str]:
    """Replay the plan: g0 holds at the start, each step's preconditions before it and g_i after it."""
    assert res.status is PlanStatus.SOLVED and res.plan is not None, res.reason
    steps = res.plan.steps
    s = state
    assert all(s.holds(a) for a in steps[0].goal.atoms)
    for st in steps[1:]:
        act = st.action
        assert all(s.holds(p) for p in act.preconditions()), act
        s = s.apply(act.effects())
        assert all(s.holds(a) for a in st.goal.atoms), (act, st.goal)
    assert set(steps[-1].goal.atoms) == set(goal.atoms)
    return [st.action.pddl() for st in steps[1:]]


def test_a_goal_free_generator_no_longer_keeps_the_forward_search_out() -> None:
    dom = _domain(Generator("where", (U,), _believed_spot, (T,), reads=reads_nothing))
    assert generators_unsupported(dom) is None
    fwd = plan(dom, _objects(), STATE, GOAL, flat_levels(), PlannerConfig(time_limit=10))
    assert fwd.method.startswith("forward"), fwd.method
    reg = plan(dom, _objects(), STATE, GOAL, flat_levels(), PlannerConfig(time_limit=10, engine="regression"))
    assert sorted(_checked(fwd, STATE, GOAL)) == sorted(_checked(reg, STATE, GOAL))
    assert "(fetch cup s2)" in _checked(fwd, STATE, GOAL)


def test_only_proposed_values_are_grounded() -> None:
    """A generator that never proposes the spot the cup is at: neither engine can fetch it."""
    def elsewhere(bindings: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
        yield {U: "s1"}

    dom = _domain(Generator("where", (U,), elsewhere, (T,), reads=reads_nothing))
    goal = Goal.of([atom("holding", "cup")])
    fwd = plan(dom, _objects(), STATE, goal, flat_levels(), PlannerConfig(time_limit=10))
    reg = plan(dom, _objects(), STATE, goal, flat_levels(), PlannerConfig(time_limit=10, engine="regression"))
    assert fwd.method.startswith("forward") and fwd.status is PlanStatus.UNSOLVABLE
    assert reg.status is PlanStatus.UNSOLVABLE


def test_an_effect_naming_every_output_keeps_every_binding() -> None:
    """place(t, u) with effect at(t, u): the regression grounder binds u from a target, no generator runs."""
    preds = {"at": Predicate("at", 2), "holding": Predicate("holding", 1)}
    place = Operator("place", (T, U), (Precondition(atom("holding", T)),),
                     (atom("at", T, U), atom("holding", T, value=False)),
                     generators=(Generator("spot", (U,), lambda b, g, bel, c: iter([{U: "s1"}]), (),
                                           reads=reads_nothing),))
    dom = Domain("placing", preds, (place,))
    f = GeneratorFilter(State([]), frozenset(SPOTS), 8)
    assert f.accepts(place, ("cup", "s3"))
    state = State([atom("holding", "cup")])
    goal = Goal.of([atom("at", "cup", "s3")])
    res = plan(dom, _objects(), state, goal, flat_levels(), PlannerConfig(time_limit=10))
    assert res.method.startswith("forward") and _checked(res, state, goal) == ["(place cup s3)"]


def _durations(bindings: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
    yield {D: 2.5}  # a number: not an object the forward task could enumerate


def _timed_domain() -> Domain:
    preds = {"at": Predicate("at", 2), "waited": Predicate("waited", 1)}
    wait = Operator("wait", (T, D), (Precondition(atom("at", T, "s2")),), (atom("waited", T),),
                    generators=(Generator("how_long", (D,), _durations, (), reads=reads_nothing),))
    return Domain("waiting", preds, (wait,))


def test_values_that_are_not_objects_go_to_the_regression_search() -> None:
    goal = Goal.of([atom("waited", "cup")])
    with pytest.raises(NotEnumerable):
        GeneratorFilter(STATE, frozenset(_objects()), 8).accepts(_timed_domain().operators[0], ("cup", "s1"))
    res = plan(_timed_domain(), _objects(), STATE, goal, flat_levels(), PlannerConfig(time_limit=10))
    assert res.status is PlanStatus.SOLVED and not res.method.startswith("forward"), res.method
    with pytest.raises(UsageError, match="not an object"):
        plan(_timed_domain(), _objects(), STATE, goal, flat_levels(), PlannerConfig(time_limit=10, engine="forward"))


def test_the_refusal_is_kept_for_the_later_calls(monkeypatch: pytest.MonkeyPatch) -> None:
    """Once a generator proposed a non-object, the domain's later calls do not ground forward again."""
    import nowplan.planning.forward as forward

    dom = _timed_domain()
    goal = Goal.of([atom("waited", "cup")])
    assert plan(dom, _objects(), STATE, goal, flat_levels(), PlannerConfig(time_limit=10)).solved
    assert "not an object" in dom.facts.derived["forward not enumerable"]
    grounded: list[Any] = []
    real = forward.forward_plan
    monkeypatch.setattr(forward, "forward_plan", lambda *a, **k: grounded.append(a) or real(*a, **k))
    res = plan(dom, _objects(), STATE, goal, flat_levels(), PlannerConfig(time_limit=10))
    assert res.solved and not res.method.startswith("forward") and not grounded


def test_a_generator_that_needs_its_context_goes_to_the_regression_search() -> None:
    """Forward grounding calls a generator with context None; one that reads the context raises there
    (a domain error in one line) and the call is planned by the regression search instead."""
    def needs_context(bindings: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
        ctx.extras  # noqa: B018  (raises AttributeError on None)
        yield from _believed_spot(bindings, goal, belief, ctx)

    from nowplan.planning.context import PlanningContext

    dom = _domain(Generator("where", (U,), needs_context, (T,), reads=reads_nothing))
    res = plan(dom, _objects(), STATE, GOAL, flat_levels(), PlannerConfig(time_limit=10), PlanningContext())
    assert res.solved and not res.method.startswith("forward"), (res.method, res.reason)
    assert "failed without a goal and context" in dom.facts.derived["forward not enumerable"]


def test_a_generator_that_reads_the_goal_keeps_the_forward_search_out() -> None:
    dom = _domain(Generator("where", (U,), _believed_spot, (T,)))
    assert "reads=reads_nothing" in (generators_unsupported(dom) or "")
    res = plan(dom, _objects(), STATE, GOAL, flat_levels(), PlannerConfig(time_limit=10))
    assert not res.method.startswith("forward")
    _checked(res, STATE, GOAL)
