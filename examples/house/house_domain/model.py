"""The house: what the robot knows about rooms, doors, a key and the things it fetches."""

from __future__ import annotations

from nowplan.api import (
    Domain, Operator, Precondition, Predicate, Var, atom, exactly_one, excludes, static,
)

o, k, d, r, r2 = (Var(n) for n in ("o", "k", "d", "r", "r2"))
# criticalities: the top level plans where items go, the robot's route and the doors (ROUTE);
# refining a step adds the gripper and where the robot stands to manipulate (REACH)
ROUTE, REACH = 2, 1

PREDICATES = {p.name: p for p in (
    Predicate("robot_in", 1, ("room",)),
    Predicate("at", 2, ("item", "room")),
    Predicate("holding", 1, ("item",)),
    Predicate("hand_empty", 0),
    Predicate("open", 1, ("door",)),
    Predicate("unlocked", 1, ("door",)),
    Predicate("connects", 3, ("door", "room", "room")),  # static: listed both ways
    Predicate("unlocks", 2, ("item", "door")),  # static: which key opens which door
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


OPERATORS = (
    Operator("move", (r, r2, d),
             (pre("robot_in", r, crit=ROUTE), static(atom("connects", d, r, r2)), pre("open", d, crit=ROUTE)),
             (atom("robot_in", r2), atom("robot_in", r, value=False)),
             param_types=("room", "room", "door")),
    Operator("open_door", (d, r, r2),
             (pre("unlocked", d, crit=ROUTE), pre("robot_in", r, crit=REACH), static(atom("connects", d, r, r2))),
             (atom("open", d),), param_types=("door", "room", "room")),
    Operator("unlock", (d, k, r, r2),
             (pre("holding", k, crit=ROUTE), static(atom("unlocks", k, d)), pre("robot_in", r, crit=REACH),
              static(atom("connects", d, r, r2))),
             (atom("unlocked", d),), param_types=("door", "item", "room", "room")),
    Operator("pick", (o, r),
             (pre("at", o, r, crit=ROUTE), pre("hand_empty", crit=REACH), pre("robot_in", r, crit=REACH)),
             (atom("holding", o), atom("at", o, r, value=False), atom("hand_empty", value=False)),
             param_types=("item", "room")),
    Operator("place", (o, r),
             (pre("holding", o, crit=ROUTE), pre("robot_in", r, crit=REACH)),
             (atom("at", o, r), atom("holding", o, value=False), atom("hand_empty")),
             param_types=("item", "room")),
)

CONFLICTS = (
    exactly_one("robot_in", key=()),  # the robot is in exactly one room
    exactly_one("at", "holding", key=0),  # an item lies in one room or is held
    excludes(atom("hand_empty"), atom("holding", o)),  # a free hand holds nothing
)

DOMAIN = Domain("house", PREDICATES, OPERATORS, types={"room": None, "door": None, "item": None},
                conflicts=CONFLICTS)
