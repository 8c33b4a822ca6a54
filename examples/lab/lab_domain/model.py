"""A lab on three floors: spots on each floor, an elevator, a lab door, a scanner tool, samples."""

from __future__ import annotations

from nowplan.api import Domain, Operator, Precondition, Predicate, Var, atom, exactly_one, excludes, static

o, t, s, s2, f, f2, d = (Var(n) for n in ("o", "t", "s", "s2", "f", "f2", "d"))
# three classes: where things go (TASK), the route between floors and through doors (ROUTE),
# what the robot must hold and where it stands (REACH)
TASK, ROUTE, REACH = 3, 2, 1

PREDICATES = {p.name: p for p in (
    Predicate("robot_at", 1, ("spot",)),
    Predicate("at", 2, ("thing", "spot")),
    Predicate("holding", 1, ("thing",)),
    Predicate("hand_empty", 0),
    Predicate("equipped", 1, ("thing",)),
    Predicate("scanned", 1, ("thing",)),
    Predicate("car_at", 1, ("floor",)),
    Predicate("open", 1, ("door",)),
    Predicate("on_floor", 2, ("spot", "floor")),  # static
    Predicate("hallway", 2, ("spot", "spot")),  # static: walkable without a door, both ways
    Predicate("through", 3, ("door", "spot", "spot")),  # static: both ways
    Predicate("lift", 2, ("spot", "floor")),  # static: the elevator's landing on a floor
    Predicate("is_tool", 1, ("thing",)),  # static
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


OPERATORS = (
    Operator("walk", (s, s2), (pre("robot_at", s, crit=ROUTE), static(atom("hallway", s, s2))),
             (atom("robot_at", s2), atom("robot_at", s, value=False)), param_types=("spot", "spot")),
    Operator("pass_door", (s, s2, d),
             (pre("robot_at", s, crit=ROUTE), static(atom("through", d, s, s2)), pre("open", d, crit=ROUTE)),
             (atom("robot_at", s2), atom("robot_at", s, value=False)), param_types=("spot", "spot", "door")),
    Operator("open_door", (d, s, s2),
             (pre("robot_at", s, crit=REACH), static(atom("through", d, s, s2)), pre("hand_empty", crit=REACH)),
             (atom("open", d),), param_types=("door", "spot", "spot")),
    Operator("call", (f, s), (pre("robot_at", s, crit=REACH), static(atom("lift", s, f))),
             (atom("car_at", f),), param_types=("floor", "spot")),
    Operator("ride", (s, s2, f, f2),
             (pre("robot_at", s, crit=ROUTE), static(atom("lift", s, f)), static(atom("lift", s2, f2)),
              pre("car_at", f, crit=ROUTE)),
             (atom("robot_at", s2), atom("robot_at", s, value=False), atom("car_at", f2), atom("car_at", f, value=False)),
             param_types=("spot", "spot", "floor", "floor")),
    Operator("pick", (o, s),
             (pre("at", o, s, crit=TASK), pre("robot_at", s, crit=REACH), pre("hand_empty", crit=REACH)),
             (atom("holding", o), atom("at", o, s, value=False), atom("hand_empty", value=False)),
             param_types=("thing", "spot")),
    Operator("place", (o, s), (pre("holding", o, crit=TASK), pre("robot_at", s, crit=REACH)),
             (atom("at", o, s), atom("holding", o, value=False), atom("hand_empty")), param_types=("thing", "spot")),
    Operator("equip", (t, s),
             (static(atom("is_tool", t)), pre("at", t, s, crit=TASK), pre("robot_at", s, crit=REACH)),
             (atom("equipped", t), atom("at", t, s, value=False)), param_types=("thing", "spot")),
    Operator("scan", (o, t, s),
             (static(atom("is_tool", t)), pre("equipped", t, crit=TASK), pre("at", o, s, crit=TASK),
              pre("robot_at", s, crit=REACH)),
             (atom("scanned", o),), param_types=("thing", "thing", "spot")),
)

CONFLICTS = (
    exactly_one("robot_at", key=()),
    exactly_one("car_at", key=()),
    exactly_one("at", "holding", "equipped", key=0),
    excludes(atom("hand_empty"), atom("holding", o)),
)

DOMAIN = Domain("lab", PREDICATES, OPERATORS, types={"spot": None, "floor": None, "door": None, "thing": None},
                conflicts=CONFLICTS)
