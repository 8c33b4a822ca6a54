"""The ferries: what the harbour master knows about boats, seats, fuel, the channel and passengers.

    harbor (fuel) --- pier ==channel (one boat at a time)== cove --- isle

Shapes: two boats of two seats each (counted slots ``seats(b, sN)``); a discrete fuel gauge per
boat (``fuel(b, fN)``, one level per sail or channel entry), refilled only at the harbour, or
anywhere by a dear tug when empty; a channel that is a shared resource one boat holds from ``enter`` to
``leave``; destinations (``wants``) that no operator changes but the passengers do (exogenous);
a goal with negative atoms (no boat in the channel, no boat left at the fuel dock); three
criticality classes.
"""

from __future__ import annotations

from nowplan.api import Domain, Operator, Precondition, Predicate, Var, at_most_one, atom, exactly_one, excludes, static

b, p, d, d2, f, f2, n, n2 = (Var(x) for x in ("b", "p", "d", "d2", "f", "f2", "n", "n2"))
# the top plans who boards which boat and gets off where; refining adds where the boats are and
# the channel; the bottom adds the fuel and the free seats (as a user first writes it)
TASK, ROUTE, LOAD = 3, 2, 1

PREDICATES = {x.name: x for x in (
    Predicate("boat_at", 2, ("boat", "dock")),
    Predicate("in_channel", 1, ("boat",)),
    Predicate("channel_free", 0),
    Predicate("fuel", 2, ("boat", "level")),
    Predicate("seats", 2, ("boat", "count")),  # free seats
    Predicate("at", 2, ("passenger", "dock")),  # waiting on a dock
    Predicate("aboard", 2, ("passenger", "boat")),
    Predicate("served", 1, ("passenger",)),  # delivered where they (last) wanted
    Predicate("wants", 2, ("passenger", "dock")),  # no operator changes it; passengers do
    # static
    Predicate("lane", 2, ("dock", "dock")),  # both ways
    Predicate("mouth", 1, ("dock",)),  # a dock at an end of the channel
    Predicate("fuel_dock", 1, ("dock",)),
    Predicate("dec", 2, ("level", "level")),  # one level less
    Predicate("below_full", 1, ("level",)),
    Predicate("full", 1, ("level",)),
    Predicate("empty", 1, ("level",)),
    Predicate("one_less", 2, ("count", "count")),  # n = n2 - 1
)}


def pre(name: str, *args: object, crit: int) -> Precondition:
    return Precondition(atom(name, *args), crit)


def burn(boat: Var, lvl: Var, lvl2: Var) -> tuple[object, ...]:
    return (atom("fuel", boat, lvl2), atom("fuel", boat, lvl, value=False))


OPERATORS = (
    Operator("sail", (b, d, d2, f, f2),
             (pre("boat_at", b, d, crit=ROUTE), static(atom("lane", d, d2)), pre("fuel", b, f, crit=LOAD),
              static(atom("dec", f, f2))),
             (atom("boat_at", b, d2), atom("boat_at", b, d, value=False)) + burn(b, f, f2),
             param_types=("boat", "dock", "dock", "level", "level")),
    Operator("enter", (b, d, f, f2),
             (pre("boat_at", b, d, crit=ROUTE), static(atom("mouth", d)), pre("channel_free", crit=ROUTE),
              pre("fuel", b, f, crit=LOAD), static(atom("dec", f, f2))),
             (atom("in_channel", b), atom("boat_at", b, d, value=False), atom("channel_free", value=False))
             + burn(b, f, f2), param_types=("boat", "dock", "level", "level")),
    Operator("leave", (b, d),
             (pre("in_channel", b, crit=ROUTE), static(atom("mouth", d))),
             (atom("boat_at", b, d), atom("in_channel", b, value=False), atom("channel_free")),
             param_types=("boat", "dock")),
    Operator("refuel", (b, d, f, f2),
             (pre("boat_at", b, d, crit=ROUTE), static(atom("fuel_dock", d)), pre("fuel", b, f, crit=LOAD),
              static(atom("below_full", f)), static(atom("full", f2))),
             (atom("fuel", b, f2), atom("fuel", b, f, value=False)), cost=2.0,
             param_types=("boat", "dock", "level", "level")),
    Operator("tug", (b, d, f, f2),  # a tug fills an empty tank anywhere, dearly
             (pre("boat_at", b, d, crit=ROUTE), pre("fuel", b, f, crit=LOAD), static(atom("empty", f)),
              static(atom("full", f2))),
             (atom("fuel", b, f2), atom("fuel", b, f, value=False)), cost=30.0,
             param_types=("boat", "dock", "level", "level")),
    Operator("board", (p, b, d, n, n2),
             (pre("at", p, d, crit=TASK), pre("boat_at", b, d, crit=ROUTE), pre("seats", b, n2, crit=LOAD),
              static(atom("one_less", n, n2))),
             (atom("aboard", p, b), atom("at", p, d, value=False), atom("seats", b, n), atom("seats", b, n2, value=False)),
             param_types=("passenger", "boat", "dock", "count", "count")),
    Operator("alight", (p, b, d, n, n2),
             (pre("aboard", p, b, crit=TASK), pre("wants", p, d, crit=TASK), pre("boat_at", b, d, crit=ROUTE),
              pre("seats", b, n, crit=LOAD), static(atom("one_less", n, n2))),
             (atom("served", p), atom("aboard", p, b, value=False), atom("seats", b, n2), atom("seats", b, n, value=False)),
             param_types=("passenger", "boat", "dock", "count", "count")),
)

CONFLICTS = (
    exactly_one("boat_at", "in_channel", key=0),  # a boat is at one dock or in the channel
    at_most_one("in_channel", key=()),  # one boat in the channel
    excludes(atom("channel_free"), atom("in_channel", b)),
    exactly_one("fuel", key=0),
    exactly_one("seats", key=0),
    exactly_one("at", "aboard", "served", key=0),  # a passenger waits, rides or is served
    exactly_one("wants", key=0),
)

DOMAIN = Domain("ferry", PREDICATES, OPERATORS,
                types={"boat": None, "dock": None, "level": None, "count": None, "passenger": None},
                conflicts=CONFLICTS)
