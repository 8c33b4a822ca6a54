"""The mine: what the rover knows about tunnels, its battery, the gate and the gem it looks for.

    shaft (base, charger) ==gate== hall --- east
                                   |  \\--- west
                      drop (1) v   ^ climb (8, two battery levels)
                                  deep

Shapes: a one-way ``drop`` whose way back (``climb``) is eight times dearer; a discrete battery
(``batt(eN)``, one level per move) recharged only at the shaft; a dear ``tow`` (25) back to the
shaft from anywhere, flat; a goal with a negative atom (``not open(gate)``: leave the gate shut,
which every trip in and out must open); a detector with false negatives *and* false positives
(``scan``); three criticality classes.
"""

from __future__ import annotations

from typing import Any

from nowplan.api import Domain, Operator, Precondition, Predicate, Var, atom, exactly_one, excludes, static

o, l, l2, e, e2, g = (Var(n) for n in ("o", "l", "l2", "e", "e2", "g"))
# the top plans what is found, picked and stored; refining adds the route, the gate and the
# battery; the bottom adds the free hand
TASK, ROUTE, REACH = 3, 2, 1
MAYBE = 0.05  # a place is worth a scan when the gem is there with at least this probability


def maybe(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``maybe(o, l)``: the belief gives the item a chance of MAYBE or more at the place."""
    p: float = belief.probability(atom("at", args[0], args[1]))
    return (p >= MAYBE) == bool(value)


def scan_cost(bindings: Any, belief: Any) -> float:
    """A scan costs more the less likely it is to find the item (1 at certainty, 1 + 6 at 0)."""
    p = belief.probability(atom("at", bindings[o], bindings[l])) if belief is not None else 0.5
    return 1.0 + 6.0 * (1.0 - p)


PREDICATES = {p.name: p for p in (
    Predicate("robot_at", 1, ("place",)),
    Predicate("batt", 1, ("level",)),
    Predicate("open", 1, ("gate",)),
    Predicate("at", 2, ("item", "place")),
    Predicate("holding", 1, ("item",)),
    Predicate("hand_empty", 0),
    Predicate("stored", 1, ("item",)),
    Predicate("maybe", 2, ("item", "place"), test=maybe),
    # static
    Predicate("tunnel", 2, ("place", "place")),  # both ways
    Predicate("gated", 3, ("gate", "place", "place")),  # both ways
    Predicate("chute", 2, ("place", "place")),  # one way down
    Predicate("dec", 2, ("level", "level")),  # one level less
    Predicate("dec2", 2, ("level", "level")),  # two levels less
    Predicate("full", 1, ("level",)),
    Predicate("base", 1, ("place",)),  # the charger, where items are stored
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


def moved(frm: Var, to: Var, lvl: Var, lvl2: Var) -> tuple[Any, ...]:
    return (atom("robot_at", to), atom("robot_at", frm, value=False), atom("batt", lvl2), atom("batt", lvl, value=False))


OPERATORS = (
    Operator("go", (l, l2, e, e2),
             (pre("robot_at", l, crit=ROUTE), static(atom("tunnel", l, l2)), pre("batt", e, crit=ROUTE),
              static(atom("dec", e, e2))),
             moved(l, l2, e, e2), param_types=("place", "place", "level", "level")),
    Operator("pass_gate", (g, l, l2, e, e2),
             (pre("open", g, crit=ROUTE), pre("robot_at", l, crit=ROUTE), static(atom("gated", g, l, l2)),
              pre("batt", e, crit=ROUTE), static(atom("dec", e, e2))),
             moved(l, l2, e, e2), param_types=("gate", "place", "place", "level", "level")),
    Operator("drop", (l, l2, e, e2),
             (pre("robot_at", l, crit=ROUTE), static(atom("chute", l, l2)), pre("batt", e, crit=ROUTE),
              static(atom("dec", e, e2))),
             moved(l, l2, e, e2), param_types=("place", "place", "level", "level")),
    Operator("climb", (l, l2, e, e2),
             (pre("robot_at", l, crit=ROUTE), static(atom("chute", l2, l)), pre("batt", e, crit=ROUTE),
              static(atom("dec2", e, e2))),
             moved(l, l2, e, e2), cost=8.0, param_types=("place", "place", "level", "level")),
    Operator("tow", (l, l2),
             (pre("robot_at", l, crit=ROUTE), static(atom("base", l2))),
             (atom("robot_at", l2), atom("robot_at", l, value=False)), cost=25.0, param_types=("place", "place")),
    Operator("charge", (l, e, e2),
             (pre("robot_at", l, crit=ROUTE), static(atom("base", l)), pre("batt", e, crit=ROUTE),
              static(atom("full", e2))),
             (atom("batt", e2), atom("batt", e, value=False)), cost=3.0, param_types=("place", "level", "level")),
    Operator("open_gate", (g, l, l2),
             (pre("robot_at", l, crit=ROUTE), static(atom("gated", g, l, l2))),
             (atom("open", g),), param_types=("gate", "place", "place")),
    Operator("close_gate", (g, l, l2),
             (pre("open", g, crit=TASK), pre("robot_at", l, crit=ROUTE), static(atom("gated", g, l, l2))),
             (atom("open", g, value=False),), param_types=("gate", "place", "place")),
    Operator("scan", (o, l), (pre("maybe", o, l, crit=TASK), pre("robot_at", l, crit=ROUTE)),
             (atom("at", o, l),), cost=scan_cost, param_types=("item", "place")),
    Operator("pick", (o, l),
             (pre("at", o, l, crit=TASK), pre("robot_at", l, crit=ROUTE), pre("hand_empty", crit=REACH)),
             (atom("holding", o), atom("at", o, l, value=False), atom("hand_empty", value=False)),
             param_types=("item", "place")),
    Operator("store", (o, l),
             (pre("holding", o, crit=TASK), static(atom("base", l)), pre("robot_at", l, crit=ROUTE)),
             (atom("stored", o), atom("holding", o, value=False), atom("hand_empty")), param_types=("item", "place")),
)

CONFLICTS = (
    exactly_one("robot_at", key=()),
    exactly_one("batt", key=()),
    excludes(atom("hand_empty"), atom("holding", o)),
)

DOMAIN = Domain("mine", PREDICATES, OPERATORS, types={"place": None, "level": None, "item": None, "gate": None},
                conflicts=CONFLICTS)
