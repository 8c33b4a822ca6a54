"""A hospital ward: a courier robot, doors that staff open and close, a bulky trolley, medication."""

from __future__ import annotations

from typing import Any

from nowplan.api import Domain, Operator, Precondition, Predicate, Var, atom, exactly_one, excludes, static

o, d, r, r2 = (Var(n) for n in ("o", "d", "r", "r2"))
# three classes: where the items end up (TASK), the doors and the route (ROUTE), where the robot
# stands and what its hand holds (REACH)
TASK, ROUTE, REACH = 3, 2, 1

MAYBE = 0.05  # a room is worth a look for an item the belief gives this chance to be there


def maybe(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``maybe(o, r)``: the belief gives the item a chance of MAYBE or more to be in the room."""
    p: float = belief.probability(atom("at", args[0], args[1]))
    return (p >= MAYBE) == bool(value)


def maybe_gone(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``maybe_gone(o, r)``: the belief gives the item a chance of MAYBE or more to be elsewhere."""
    p: float = belief.probability(atom("at", args[0], args[1]))
    return (p <= 1.0 - MAYBE) == bool(value)


PREDICATES = {p.name: p for p in (
    Predicate("robot_in", 1, ("room",)),
    Predicate("at", 2, ("item", "room")),
    Predicate("holding", 1, ("item",)),
    Predicate("hand_empty", 0),
    Predicate("open", 1, ("door",)),
    Predicate("connects", 3, ("door", "room", "room")),  # static, both ways
    Predicate("portable", 1, ("item",)),  # static: carried in the gripper
    Predicate("bulky", 1, ("item",)),  # static: only pushed, through an open door
    Predicate("maybe", 2, ("item", "room"), test=maybe),
    Predicate("maybe_gone", 2, ("item", "room"), test=maybe_gone),
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


OPERATORS = (
    Operator("move", (r, r2, d),
             (pre("robot_in", r, crit=ROUTE), static(atom("connects", d, r, r2)), pre("open", d, crit=ROUTE)),
             (atom("robot_in", r2), atom("robot_in", r, value=False)), param_types=("room", "room", "door")),
    Operator("open_door", (d, r, r2),
             (pre("robot_in", r, crit=REACH), static(atom("connects", d, r, r2))),
             (atom("open", d),), param_types=("door", "room", "room")),
    Operator("close_door", (d, r, r2),
             (pre("robot_in", r, crit=REACH), static(atom("connects", d, r, r2))),
             (atom("open", d, value=False),), param_types=("door", "room", "room")),
    Operator("pick", (o, r),
             (static(atom("portable", o)), pre("at", o, r, crit=TASK), pre("robot_in", r, crit=REACH),
              pre("hand_empty", crit=REACH)),
             (atom("holding", o), atom("at", o, r, value=False), atom("hand_empty", value=False)),
             param_types=("item", "room")),
    Operator("place", (o, r), (pre("holding", o, crit=TASK), pre("robot_in", r, crit=REACH)),
             (atom("at", o, r), atom("holding", o, value=False), atom("hand_empty")), param_types=("item", "room")),
    Operator("push", (o, r, r2, d),
             (static(atom("bulky", o)), pre("at", o, r, crit=TASK), static(atom("connects", d, r, r2)),
              pre("open", d, crit=ROUTE), pre("robot_in", r, crit=REACH), pre("hand_empty", crit=REACH)),
             (atom("at", o, r2), atom("at", o, r, value=False), atom("robot_in", r2), atom("robot_in", r, value=False)),
             cost=2.0, param_types=("item", "room", "room", "door")),
    # looks: the robot sees its room after every action; these say what a look there may teach.
    # Their effects are what the robot hopes to learn (neither the world nor the belief applies them)
    Operator("seek", (o, r), (pre("maybe", o, r, crit=TASK), pre("robot_in", r, crit=REACH)),
             (atom("at", o, r),), cost=2.0, param_types=("item", "room")),
    Operator("check_gone", (o, r), (pre("maybe_gone", o, r, crit=TASK), pre("robot_in", r, crit=REACH)),
             (atom("at", o, r, value=False),),
             cost=1.0, param_types=("item", "room")),
)
LOOKS = ("seek", "check_gone")

CONFLICTS = (
    exactly_one("robot_in", key=()),
    exactly_one("at", "holding", key=0),
    excludes(atom("hand_empty"), atom("holding", o)),
)

DOMAIN = Domain("ward", PREDICATES, OPERATORS, types={"room": None, "door": None, "item": None},
                conflicts=CONFLICTS)
