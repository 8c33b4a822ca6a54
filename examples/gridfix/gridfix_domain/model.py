"""Gridfix: a line crew's van restores a storm-damaged radial feeder.

    roads (each drive spends one battery level; docks charge and sell spares)

        depot(dock) ---- sub(dock) ---- j1 ---- j2 ---- j3
            |                                   |     /
            +---------------- j4 ---------------+----+      (j2-j4, j3-j4, j4-depot)

    wires (what feeds what; each segment is worked on from its downstream end)

        sub --c1--> j1 --c2--> j2 --c3--> j3
                               |
                               +--c4--> j4

Shapes the other examples do not have:

* the hidden facts are *attributes* of fixed objects (``ok(c)``: the segment is intact), jointly
  distributed (a storm broke one or two of four), not where an item lies;
* the agent learns from its own failures: closing a breaker onto a broken segment trips (the world
  refuses the action with its reason) and the belief weighs that failure as evidence;
* a telemetry reading (which junctions are live) is seen everywhere, and a junction going dead by
  itself tells the belief that some segment upstream broke (a group test, not a look at one thing);
* two bounded counters: the battery (``batt(e0..e4)``, recharged at two docks) and the spares the
  van carries (``spares(s0..s2)``, bought at a dock, used up by a replacement, even of an intact
  segment);
* a sensing action (``inspect``) competes with a sure but dear one (``replace``): the planner
  should test first where the segment is likely intact;
* a tidy-up goal atom (park the van at the depot) that holds at the start.
"""

from __future__ import annotations

from typing import Any

from nowplan.api import Domain, Operator, Precondition, Predicate, Var, atom, exactly_one, static

c, a, b, u, v, e, e2, n, n2 = (Var(x) for x in ("c", "a", "b", "u", "v", "e", "e2", "n", "n2"))
# the top plans which segments are made good and which junctions energised; refinement adds the spares
# the van carries; the bottom adds where the van is and its battery (the route)
TASK, SUPPLY, ROUTE = 3, 2, 1
MAYBE = 0.15  # a segment is worth inspecting when the belief gives it at least this chance to be intact


def maybe_ok(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``maybe_ok(c)``: the belief gives segment ``c`` a chance of MAYBE or more to be intact."""
    p: float = belief.probability(atom("ok", args[0]))
    return (p >= MAYBE) == bool(value)


def inspect_cost(bindings: Any, belief: Any) -> float:
    """An inspection costs more the likelier the segment is broken (it will probably just say so)."""
    p = belief.probability(atom("ok", bindings[c])) if belief is not None and c in bindings else 0.5
    return 1.0 + 6.0 * (1.0 - p)


PREDICATES = {x.name: x for x in (
    Predicate("van_at", 1, ("site",)),
    Predicate("batt", 1, ("level",)),
    Predicate("spares", 1, ("stock",)),
    Predicate("ok", 1, ("segment",)),  # hidden: the segment is intact
    Predicate("live", 1, ("site",)),  # the junction is energised (telemetry: always seen)
    Predicate("maybe_ok", 1, ("segment",), test=maybe_ok),
    # static
    Predicate("road", 2, ("site", "site")),  # both ways
    Predicate("dock", 1, ("site",)),  # charges the van and sells spares
    Predicate("feeds", 3, ("segment", "site", "site")),  # feeds(c, u, v): segment c carries u's power to v
    Predicate("works_at", 2, ("segment", "site")),  # where the crew works on the segment
    Predicate("dec", 2, ("level", "level")),  # one battery level less
    Predicate("full", 1, ("level",)),
    Predicate("less", 2, ("stock", "stock")),  # less(n, n2): one spare fewer in n2 than in n
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


OPERATORS = (
    Operator("drive", (a, b, e, e2),
             (pre("van_at", a, crit=ROUTE), static(atom("road", a, b)), pre("batt", e, crit=ROUTE),
              static(atom("dec", e, e2))),
             (atom("van_at", b), atom("van_at", a, value=False), atom("batt", e2), atom("batt", e, value=False)),
             param_types=("site", "site", "level", "level")),
    Operator("charge", (a, e, e2),
             (pre("van_at", a, crit=ROUTE), static(atom("dock", a)), pre("batt", e, crit=ROUTE),
              static(atom("full", e2))),
             (atom("batt", e2), atom("batt", e, value=False)), cost=2.0, param_types=("site", "level", "level")),
    Operator("tow", (a, b),  # a dear way back from anywhere (a flat battery is no dead end)
             (pre("van_at", a, crit=ROUTE), static(atom("dock", b))),
             (atom("van_at", b), atom("van_at", a, value=False)), cost=25.0, param_types=("site", "site")),
    Operator("buy", (a, n, n2),
             (pre("van_at", a, crit=ROUTE), static(atom("dock", a)), pre("spares", n, crit=SUPPLY),
              static(atom("less", n2, n))),
             (atom("spares", n2), atom("spares", n, value=False)), param_types=("site", "stock", "stock")),
    # the look: its effect is what the crew hopes to learn (neither world nor belief applies it)
    Operator("inspect", (c, a),
             (pre("maybe_ok", c, crit=TASK), static(atom("works_at", c, a)), pre("van_at", a, crit=ROUTE)),
             (atom("ok", c),), cost=inspect_cost, param_types=("segment", "site")),
    Operator("replace", (c, a, n, n2),
             (static(atom("works_at", c, a)), pre("spares", n, crit=SUPPLY), static(atom("less", n, n2)),
              pre("van_at", a, crit=ROUTE)),
             (atom("ok", c), atom("spares", n2), atom("spares", n, value=False)), cost=4.0,
             param_types=("segment", "site", "stock", "stock")),
    Operator("close", (c, u, v, a),
             (static(atom("feeds", c, u, v)), pre("live", u, crit=TASK), pre("ok", c, crit=TASK),
              static(atom("works_at", c, a)), pre("van_at", a, crit=ROUTE)),
             (atom("live", v),), param_types=("segment", "site", "site", "site")),
)
LOOKS = ("inspect",)

CONFLICTS = (
    exactly_one("van_at", key=()),
    exactly_one("batt", key=()),
    exactly_one("spares", key=()),
)

DOMAIN = Domain("gridfix", PREDICATES, OPERATORS,
                types={"site": None, "segment": None, "level": None, "stock": None}, conflicts=CONFLICTS)
