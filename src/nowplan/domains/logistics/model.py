"""Hierarchical logistics, written in Python: packages, trucks, airplanes, cities.

Criticalities make it hierarchical in HPN's way: at the top level (1) only
where the *packages* are matters (a load needs the package at the place, an
unload needs it inside the vehicle); at level 0 the vehicles' positions are
added, so driving and flying appear only when a load or unload is refined.
Static facts (which city a place is in, which city a truck serves, which
places are airports) are checked at every level, which keeps the downward
refinement property: every abstract plan can be refined.
"""

from __future__ import annotations

from nowplan.core.atoms import Atom, AtMostOne, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.operators import Operator, Precondition, Resource, ResourceUse

PKG = 2  # criticality of package-position preconditions
VEH = 1  # criticality of vehicle-position preconditions

p, t, a, l, l2, c = (Var(n) for n in ("p", "t", "a", "l", "l2", "c"))

PREDICATES = {
    "at": Predicate("at", 2, (None, "location")),
    "in": Predicate("in", 2, ("package", None)),
    "in_city": Predicate("in_city", 2, ("location", "city")),
    "serves": Predicate("serves", 2, ("truck", "city")),
    "airport": Predicate("airport", 1, ("location",)),
}

TYPES = {
    "package": None,
    "vehicle": None,
    "truck": "vehicle",
    "airplane": "vehicle",
    "location": None,
    "city": None,
}


def _pre(x: Atom, crit: int) -> Precondition:
    return Precondition(x, crit)


OPERATORS = (
    Operator(
        "load_truck", (p, t, l, c),
        (_pre(atom("at", p, l), PKG), _pre(atom("in_city", l, c), PKG), _pre(atom("serves", t, c), PKG),
         _pre(atom("at", t, l), VEH)),
        (atom("in", p, t), atom("at", p, l, value=False)),
        cost=1.0, param_types=("package", "truck", "location", "city"),
        resources=(Resource(("vehicle", t), ResourceUse.SHAREABLE), Resource(("place", l), ResourceUse.CONTAINED)),
    ),
    Operator(
        "unload_truck", (p, t, l, c),
        (_pre(atom("in", p, t), PKG), _pre(atom("in_city", l, c), PKG), _pre(atom("serves", t, c), PKG),
         _pre(atom("at", t, l), VEH)),
        (atom("at", p, l), atom("in", p, t, value=False)),
        cost=1.0, param_types=("package", "truck", "location", "city"),
        resources=(Resource(("vehicle", t), ResourceUse.SHAREABLE), Resource(("place", l), ResourceUse.CONTAINED)),
    ),
    Operator(
        "drive_truck", (t, l, l2, c),
        (_pre(atom("at", t, l), VEH), _pre(atom("in_city", l, c), VEH), _pre(atom("in_city", l2, c), VEH),
         _pre(atom("serves", t, c), VEH)),
        (atom("at", t, l2), atom("at", t, l, value=False)),
        cost=1.0, param_types=("truck", "location", "location", "city"),
        resources=(Resource(("vehicle", t), ResourceUse.CONTAINED),),
    ),
    Operator(
        "load_airplane", (p, a, l),
        (_pre(atom("at", p, l), PKG), _pre(atom("airport", l), PKG), _pre(atom("at", a, l), VEH)),
        (atom("in", p, a), atom("at", p, l, value=False)),
        cost=1.0, param_types=("package", "airplane", "location"),
        resources=(Resource(("vehicle", a), ResourceUse.SHAREABLE), Resource(("place", l), ResourceUse.CONTAINED)),
    ),
    Operator(
        "unload_airplane", (p, a, l),
        (_pre(atom("in", p, a), PKG), _pre(atom("airport", l), PKG), _pre(atom("at", a, l), VEH)),
        (atom("at", p, l), atom("in", p, a, value=False)),
        cost=1.0, param_types=("package", "airplane", "location"),
        resources=(Resource(("vehicle", a), ResourceUse.SHAREABLE), Resource(("place", l), ResourceUse.CONTAINED)),
    ),
    Operator(
        "fly_airplane", (a, l, l2),
        (_pre(atom("at", a, l), VEH), _pre(atom("airport", l), VEH), _pre(atom("airport", l2), VEH)),
        (atom("at", a, l2), atom("at", a, l, value=False)),
        cost=1.0, param_types=("airplane", "location", "location"),
        resources=(Resource(("vehicle", a), ResourceUse.CONTAINED),),
    ),
)


# an object is at one location or in one vehicle at a time
ONE_PLACE = AtMostOne(("at", "in"))


DOMAIN = Domain("logistics", PREDICATES, OPERATORS, TYPES, conflicts=(ONE_PLACE,))
