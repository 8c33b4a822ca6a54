"""A particle belief that is sure of a fluent neither way: neither the fluent nor its negation holds.

Found by a held-out domain (examples/ward): its goal ``not open(d_iso)`` held in the belief while the
odds of the door being open were 1 in 2 (the believed state is a closed world: a fluent below the
threshold was absent, so its negation held), and runs "reached" the goal with the door open.
"""

from __future__ import annotations

from nowplan.api import (
    Domain, Goal, Operator, Observation, ParticleBelief, Precondition, Predicate, State, Var, atom, plan,
)
from nowplan.belief.particle_belief import UNKNOWN
from nowplan.belief.protocols import HasUnknowns, capabilities
from nowplan.planning.task import forward_unsupported

d, r = Var("d"), Var("r")
PREDICATES = {p.name: p for p in (Predicate("open", 1, ("door",)), Predicate("here", 1, ("room",)),
                                  Predicate("by", 2, ("door", "room")))}
OPERATORS = (
    Operator("close", (d, r), (Precondition(atom("here", r), 1), Precondition(atom("by", d, r), 1)),
             (atom("open", d, value=False),), param_types=("door", "room")),
    Operator("open_it", (d, r), (Precondition(atom("here", r), 1), Precondition(atom("by", d, r), 1)),
             (atom("open", d),), param_types=("door", "room")),
)
DOMAIN = Domain("doors", PREDICATES, OPERATORS, types={"door": None, "room": None})
OBJECTS = {"d1": "door", "hall": "room"}
BASE = [atom("here", "hall"), atom("by", "d1", "hall")]


def belief(p_open: float, n: int = 20) -> ParticleBelief:
    k = round(p_open * n)
    return ParticleBelief([State(BASE + [atom("open", "d1")])] * k + [State(BASE)] * (n - k), seed=0)


def test_an_even_chance_is_unknown_either_way() -> None:
    b = belief(0.5)
    assert isinstance(b, HasUnknowns) and "unknowns" in capabilities(b)
    assert b.unknowns() == frozenset({("open", ("d1",))})
    assert b.value(("open", ("d1",))) is UNKNOWN
    assert not DOMAIN.holds(atom("open", "d1"), b)
    assert not DOMAIN.holds(atom("open", "d1", value=False), b)  # it held before: closed world


def test_sure_beliefs_keep_their_answers() -> None:
    for p, is_open in ((1.0, True), (0.95, True), (0.0, False), (0.05, False)):
        b = belief(p)
        assert b.unknowns() == frozenset()
        assert DOMAIN.holds(atom("open", "d1"), b) is is_open
        assert DOMAIN.holds(atom("open", "d1", value=False), b) is not is_open


def test_the_planner_closes_a_door_it_is_unsure_of() -> None:
    goal = Goal.of([atom("open", "d1", value=False)], DOMAIN.rules)
    unsure = plan(DOMAIN, OBJECTS, belief(0.5), goal)
    assert unsure.solved and unsure.plan is not None
    assert [a.name for a in unsure.plan.actions] == ["close"]
    sure = plan(DOMAIN, OBJECTS, belief(0.0), goal)
    assert sure.solved and sure.plan is not None and sure.plan.actions == ()


def test_forward_search_leaves_an_unsure_belief_to_the_regression_search() -> None:
    assert forward_unsupported(DOMAIN, belief(0.0)) is None
    why = forward_unsupported(DOMAIN, belief(0.5))
    assert why is not None and "unsure" in why


def test_a_look_that_settles_the_door_makes_it_known() -> None:
    b = belief(0.5)
    close = OPERATORS[0].instantiate({d: "d1", r: "hall"})
    b.update(close, Observation(True, State(BASE)))  # the door is seen shut
    assert b.unknowns() == frozenset()
    assert DOMAIN.holds(atom("open", "d1", value=False), b)


def test_unknown_compares_as_no_value() -> None:
    assert not (UNKNOWN >= 0.5) and not (UNKNOWN <= 0.5) and not bool(UNKNOWN)
    assert UNKNOWN != True  # noqa: E712 (the value rule compares with ==)
