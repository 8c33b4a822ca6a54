"""The warehouse as the robot knows it: aisles, shelf slots holding stacks of boxes, a battery.

A slot holds one stack; ``on(box, support)`` says what a box stands on (a slot or another box),
``in_slot(box, slot)`` which stack it belongs to, ``clear(support)`` that nothing stands on it.
A box lower in a stack is reachable only after the ones above it are put somewhere else.
The battery has discrete levels ``e0 .. eN``: every drive takes one (``dec(hi, lo)``) and must
leave enough to get back to the dock (``enough(loc, level)``, a reserve); the dock recharges to
full, and ``call_crew`` (dear) recharges anywhere.  Without the reserve the top plan, which does
not drive, sent the robot to the far aisle on its last level, a worker moved the box meanwhile,
and the refinement had to find the crew (a dead end is a model's to prevent: the drone's lesson
in docs/writing-a-domain.md).
"""

from __future__ import annotations

from nowplan.api import (
    Atom, Domain, Operator, Precondition, Predicate, Var, at_most_one, atom, exactly_one, excludes, static,
)

b, u, s, l, l2, e, e2, f = (Var(n) for n in ("b", "u", "s", "l", "l2", "e", "e2", "f"))
# top: what stands on what, what the robot holds, the route and the battery (whether a plan can
# work); then which supports are clear (which boxes must be moved aside first, and where to);
# at the bottom where the robot stands to manipulate and whether its hand is free (how)
ROUTE, STACK, REACH = 3, 2, 1

PREDICATES = {p.name: p for p in (
    Predicate("robot_at", 1, ("loc",)),
    Predicate("batt", 1, ("level",)),
    Predicate("on", 2, ("box", "support")),
    Predicate("in_slot", 2, ("box", "slot")),
    Predicate("clear", 1, ("support",)),
    Predicate("holding", 1, ("box",)),
    Predicate("hand_empty", 0),
    Predicate("road", 2, ("loc", "loc")),  # static, listed both ways
    Predicate("slot_at", 2, ("slot", "loc")),  # static
    Predicate("dec", 2, ("level", "level")),  # static: one drive takes the battery from hi to lo
    Predicate("enough", 2, ("loc", "level")),  # static: from here the dock is at most that many drives away
    Predicate("low", 1, ("level",)),  # static: every level but full
    Predicate("full", 1, ("level",)),  # static
    Predicate("dock", 1, ("loc",)),  # static
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


def manip(name: str, params: tuple[Var, ...], types: tuple[str, ...], need: tuple[Precondition, ...],
          effects: tuple[Atom, ...]) -> Operator:
    """A pick or a put at slot ``s`` of location ``l``: the robot stands there (REACH)."""
    return Operator(name, params, need + (pre("robot_at", l, crit=REACH), static(atom("slot_at", s, l))),
                    effects, param_types=types)


OPERATORS = (
    Operator("drive", (l, l2, e, e2),
             (pre("robot_at", l, crit=ROUTE), static(atom("road", l, l2)), pre("batt", e, crit=ROUTE),
              static(atom("dec", e, e2)), static(atom("enough", l2, e2))),
             (atom("robot_at", l2), atom("robot_at", l, value=False), atom("batt", e2), atom("batt", e, value=False)),
             param_types=("loc", "loc", "level", "level")),
    Operator("charge", (l, e, f),
             (pre("robot_at", l, crit=ROUTE), static(atom("dock", l)), pre("batt", e, crit=ROUTE),
              static(atom("low", e)), static(atom("full", f))),
             (atom("batt", f), atom("batt", e, value=False)), param_types=("loc", "level", "level")),
    Operator("call_crew", (l, e, f),  # a crew brings a fresh battery anywhere: dear
             (pre("robot_at", l, crit=ROUTE), pre("batt", e, crit=ROUTE), static(atom("low", e)),
              static(atom("full", f))),
             (atom("batt", f), atom("batt", e, value=False)), cost=25.0, param_types=("loc", "level", "level")),
    # take the bottom box of a stack (it stands on the slot itself)
    manip("pick", (b, s, l), ("box", "slot", "loc"),
          (pre("on", b, s, crit=ROUTE), pre("clear", b, crit=STACK), pre("in_slot", b, s, crit=ROUTE),
           pre("hand_empty", crit=REACH)),
          (atom("holding", b), atom("on", b, s, value=False), atom("in_slot", b, s, value=False), atom("clear", s),
           atom("hand_empty", value=False))),
    # take a box off the box ``u`` below it
    manip("unstack", (b, u, s, l), ("box", "box", "slot", "loc"),
          (pre("on", b, u, crit=ROUTE), pre("clear", b, crit=STACK), pre("in_slot", b, s, crit=ROUTE),
           pre("hand_empty", crit=REACH)),
          (atom("holding", b), atom("on", b, u, value=False), atom("in_slot", b, s, value=False), atom("clear", u),
           atom("hand_empty", value=False))),
    # put the held box on an empty slot
    manip("put", (b, s, l), ("box", "slot", "loc"),
          (pre("holding", b, crit=ROUTE), pre("clear", s, crit=STACK)),
          (atom("on", b, s), atom("in_slot", b, s), atom("clear", s, value=False), atom("holding", b, value=False),
           atom("hand_empty"))),
    # put the held box on top of the stack in slot ``s`` whose top is ``u``
    manip("stack", (b, u, s, l), ("box", "box", "slot", "loc"),
          (pre("holding", b, crit=ROUTE), pre("clear", u, crit=STACK), pre("in_slot", u, s, crit=ROUTE)),
          (atom("on", b, u), atom("in_slot", b, s), atom("clear", u, value=False), atom("holding", b, value=False),
           atom("hand_empty"))),
)

CONFLICTS = (
    exactly_one("robot_at", key=()),
    exactly_one("batt", key=()),
    exactly_one("on", "holding", key=0),  # a box stands on one thing or is held
    exactly_one("in_slot", "holding", key=0),  # a box is in one stack or is held
    at_most_one("on", key=1),  # at most one box stands on a support
    at_most_one("holding", key=()),  # one gripper
    excludes(atom("clear", u), atom("on", b, u)),
    excludes(atom("clear", s), atom("in_slot", b, s)),  # a slot holding a stack is not empty
    excludes(atom("hand_empty"), atom("holding", b)),
)

DOMAIN = Domain("warehouse", PREDICATES, OPERATORS,
                types={"loc": None, "level": None, "support": None, "box": "support", "slot": "support"},
                conflicts=CONFLICTS)
