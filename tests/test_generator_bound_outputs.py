"""A generator some of whose outputs the goal binds already (held-out tidy house, helper heldout14).

``place(thing, spot, room)`` has one generator for ``(spot, room)``; the goal ``on(cup, rack)``
binds ``spot`` through the effect, so the generator runs with ``spot`` bound and its proposals
of other spots are skipped.  Skipped proposals must not use up ``max_generator_values`` (the
bound value came ninth, after eight others, and the goal was "unsolvable"), drawing must stay
bounded for a generator that never proposes the bound value, and a plan that fails for it must
name the generator.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator, Mapping
from typing import Any

from nowplan.api import (
    Domain, Generator, Goal, Operator, PlannerConfig, PlanStatus, Precondition, Predicate, State, Var, atom,
    flat_levels, plan, reads_nothing,
)

T, U, R = Var("t"), Var("u"), Var("r")
SPOTS = [f"s{i}" for i in range(9)] + ["rack"]
ROOM = {s: ("bath" if s == "rack" else "hall") for s in SPOTS}


def _domain(gen_fn: Any) -> Domain:
    preds = {"holding": Predicate("holding", 1), "on": Predicate("on", 2), "in": Predicate("in", 2)}
    place = Operator(
        "place", (T, U, R),
        (Precondition(atom("holding", T)), Precondition(atom("in", U, R))),
        (atom("on", T, U), atom("holding", T, value=False)),
        generators=(Generator("spot", (U, R), gen_fn, (), reads=reads_nothing),),
    )
    return Domain("shelves", preds, (place,))


def _objects() -> dict[str, str | None]:
    return {"cup": None, "hall": None, "bath": None, **{s: None for s in SPOTS}}


def _state() -> State:
    return State([atom("holding", "cup"), *(atom("in", s, ROOM[s]) for s in SPOTS)])


def _in_order(bindings: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
    for s in SPOTS:  # the rack comes after nine other spots: past the default max_generator_values (8)
        yield {U: s, R: ROOM[s]}


def _never_the_rack(bindings: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
    for i in itertools.count():  # endless, and never the bound value
        yield {U: f"s{i % 9}", R: "hall"}


GOAL = Goal.of([atom("on", "cup", "rack")])


def test_skipped_proposals_do_not_use_up_the_generators_values() -> None:
    res = plan(_domain(_in_order), _objects(), _state(), GOAL, flat_levels(), PlannerConfig(time_limit=10))
    assert res.status is PlanStatus.SOLVED, res.reason
    assert res.plan is not None
    assert [s.action.pddl() for s in res.plan.steps[1:] if s.action is not None] == ["(place cup rack bath)"]


def test_a_generator_ignoring_its_bound_output_ends_and_is_named() -> None:
    res = plan(_domain(_never_the_rack), _objects(), _state(), GOAL, flat_levels(), PlannerConfig(time_limit=10))
    assert res.status is PlanStatus.UNSOLVABLE
    assert "generator spot of operator place" in res.reason and "?u" in res.reason, res.reason
