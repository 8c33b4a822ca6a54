"""The tidy house: what the robot knows about rooms, doors, surfaces and the things stacked on them.

    kitchen ==d_arch== living
       |d_kitchen        |d_living
      hall -----------------
       |d_bed (locked; its key lies under the cup on the counter)
    bedroom --d_bath-- bath

Shapes: things stacked on things (``on``/``clear``: the top ones must go first); what is put
aside goes on any support (``DOMAIN``) or on a free floor spot a generator proposes from the
belief (``DOMAIN_SPOTS``, scenario ``spots``); costs that differ a lot (a high shelf 3, unlocking 2, calling the owner to unlock any door 40); three criticality
classes.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from dataclasses import replace
from typing import Any

from nowplan.api import (
    Domain, Generator, Operator, Precondition, Predicate, Var, at_most_one, atom, excludes, exactly_one,
    reads_nothing, static,
)

o, u, r, r2, d, k = (Var(n) for n in ("o", "u", "r", "r2", "d", "k"))
# the top plans which thing goes where, what lies on it, the keys, the doors and the robot's
# route; refining adds the free hand; the bottom adds where the robot stands to reach (a first
# version kept ``clear`` and the surface's room a class below: its top plans were not refinable)
TASK, ROUTE, REACH = 3, 2, 1
HIGH = ("shelf",)  # a high surface: placing there is slow
FLOOR = "f_"  # floor spots are surfaces whose names start so


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


class PlaceCost:
    """Placing costs 1, on a high shelf 3 (a plain function of the arguments)."""

    def __call__(self, bindings: Mapping[Var, Any], belief: Any = None) -> float:
        return 3.0 if str(bindings.get(u)) in HIGH else 1.0


def free_spots(bindings: Mapping[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """Where to put a thing down when no goal says where (``u`` unbound): the free floor spots of
    the robot's room first, then of the other rooms (as the belief has them).  (A first version
    also output ``r``; the engine calls a generator whenever one of its outputs is unbound, and it
    then yielded nothing for a goal's ``on(cup, rack)``: "unsolvable".)"""
    if belief is None:
        return
    here = {str(x) for (x,) in belief.facts("robot_in")}
    clear = {str(x) for (x,) in belief.facts("clear")}
    spots = [(str(s), str(rm)) for (s, rm) in belief.facts("in") if str(s).startswith(FLOOR) and str(s) in clear]
    for s, _ in sorted(spots, key=lambda x: (x[1] not in here, x)):
        yield {u: s}


PREDICATES = {p.name: p for p in (
    Predicate("robot_in", 1, ("room",)),
    Predicate("in", 2, ("support", "room")),  # where a thing lies, or a surface stands
    Predicate("on", 2, ("thing", "support")),
    Predicate("clear", 1, ("support",)),
    Predicate("holding", 1, ("thing",)),
    Predicate("hand_empty", 0),
    Predicate("open", 1, ("door",)),
    Predicate("unlocked", 1, ("door",)),
    Predicate("connects", 3, ("door", "room", "room")),  # static, both ways
    Predicate("opens", 2, ("key", "door")),  # static
)}

OPERATORS = (
    Operator("move", (r, r2, d),
             (pre("robot_in", r, crit=TASK), static(atom("connects", d, r, r2)), pre("open", d, crit=TASK)),
             (atom("robot_in", r2), atom("robot_in", r, value=False)), param_types=("room", "room", "door")),
    Operator("open_door", (d, r, r2),
             (pre("unlocked", d, crit=TASK), pre("robot_in", r, crit=REACH), static(atom("connects", d, r, r2))),
             (atom("open", d),), param_types=("door", "room", "room")),
    Operator("close_door", (d, r, r2),
             (pre("open", d, crit=TASK), pre("robot_in", r, crit=REACH), static(atom("connects", d, r, r2))),
             (atom("open", d, value=False),), param_types=("door", "room", "room")),
    Operator("unlock", (d, k, r, r2),
             (pre("holding", k, crit=TASK), static(atom("opens", k, d)), pre("robot_in", r, crit=REACH),
              static(atom("connects", d, r, r2))),
             (atom("unlocked", d),), cost=2.0, param_types=("door", "key", "room", "room")),
    Operator("call_owner", (d,), (), (atom("unlocked", d),), cost=40.0, param_types=("door",)),
    Operator("pick", (o, u, r),
             (pre("on", o, u, crit=TASK), pre("in", o, r, crit=TASK), pre("clear", o, crit=TASK),
              pre("hand_empty", crit=ROUTE), pre("robot_in", r, crit=REACH)),
             (atom("holding", o), atom("on", o, u, value=False), atom("in", o, r, value=False), atom("clear", u),
              atom("hand_empty", value=False)),
             param_types=("thing", "support", "room")),
    Operator("place", (o, u, r),
             (pre("holding", o, crit=TASK), pre("clear", u, crit=TASK), pre("in", u, r, crit=TASK),
              pre("robot_in", r, crit=REACH)),
             (atom("on", o, u), atom("in", o, r), atom("holding", o, value=False), atom("hand_empty"),
              atom("clear", u, value=False)),
             cost=PlaceCost(), param_types=("thing", "support", "room")),
)

CONFLICTS = (
    exactly_one("robot_in", key=()),
    at_most_one("holding", key=()),  # one gripper
    at_most_one("on", "holding", key=0),  # a thing lies on one support or is held
    at_most_one("in", "holding", key=0),
    at_most_one("on", key=1),  # one thing on a support
    excludes(atom("clear", u), atom("on", o, u)),
    excludes(atom("hand_empty"), atom("holding", o)),
)

TYPES = {"room": None, "door": None, "support": None, "thing": "support", "surface": "support", "key": "thing"}
DOMAIN = Domain("tidy", PREDICATES, OPERATORS, types=TYPES, conflicts=CONFLICTS)
# the same house where a thing put aside goes to a spot the generator ``spot`` proposes (free
# floor spots, the robot's room first) instead of any support of the problem's objects
SPOT_OPERATORS = tuple(replace(op, generators=(Generator("spot", (u,), free_spots, (), reads=reads_nothing),))
                       if op.name == "place" else op for op in OPERATORS)
DOMAIN_SPOTS = Domain("tidy", PREDICATES, SPOT_OPERATORS, types=TYPES, conflicts=CONFLICTS)
