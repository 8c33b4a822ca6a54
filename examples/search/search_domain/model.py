"""Tidying up: items lie at places the robot is unsure of; it looks (and may miss), picks, and stores them."""

from __future__ import annotations

from typing import Any

from nowplan.api import Domain, Operator, Precondition, Predicate, Var, atom, exactly_one, excludes, static

o, l, l2 = Var("o"), Var("l"), Var("l2")
TASK, REACH = 2, 1
MAYBE = 0.02  # a place is worth a look when the item is there with at least this probability


def maybe(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``maybe(o, l)``: the belief gives the item a chance of MAYBE or more to lie at the place."""
    p: float = belief.probability(atom("at", args[0], args[1]))
    return (p >= MAYBE) == bool(value)


def look_cost(bindings: Any, belief: Any) -> float:
    """A look costs more the less likely it is to find the item (1 at certainty, 1 + 10 at 0)."""
    p = belief.probability(atom("at", bindings[o], bindings[l])) if belief is not None else 0.5
    return 1.0 + 10.0 * (1.0 - p)


PREDICATES = {p.name: p for p in (
    Predicate("robot_at", 1, ("place",)),
    Predicate("at", 2, ("item", "place")),
    Predicate("holding", 1, ("item",)),
    Predicate("hand_empty", 0),
    Predicate("stored", 1, ("item",)),
    Predicate("maybe", 2, ("item", "place"), test=maybe),
    Predicate("adjacent", 2, ("place", "place")),  # static
    Predicate("base", 1, ("place",)),  # static: where items are stored
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


OPERATORS = (
    Operator("go", (l, l2), (pre("robot_at", l, crit=REACH), static(atom("adjacent", l, l2))),
             (atom("robot_at", l2), atom("robot_at", l, value=False)), param_types=("place", "place")),
    Operator("look", (o, l), (pre("maybe", o, l, crit=TASK), pre("robot_at", l, crit=REACH)),
             (atom("at", o, l),), cost=look_cost, param_types=("item", "place")),
    Operator("pick", (o, l),
             (pre("at", o, l, crit=TASK), pre("robot_at", l, crit=REACH), pre("hand_empty", crit=REACH)),
             (atom("holding", o), atom("at", o, l, value=False), atom("hand_empty", value=False)),
             param_types=("item", "place")),
    Operator("store", (o, l),
             (pre("holding", o, crit=TASK), static(atom("base", l)), pre("robot_at", l, crit=REACH)),
             (atom("stored", o), atom("holding", o, value=False), atom("hand_empty")), param_types=("item", "place")),
)

CONFLICTS = (
    exactly_one("robot_at", key=()),
    excludes(atom("hand_empty"), atom("holding", o)),
)

DOMAIN = Domain("search", PREDICATES, OPERATORS, types={"place": None, "item": None}, conflicts=CONFLICTS)
