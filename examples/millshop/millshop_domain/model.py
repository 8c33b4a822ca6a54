"""The mill shop: what the cell controller knows about AGVs, blanks, two machines and the orders.

    store ---- lathe
      |          |
    dock  ---- booth

Shapes: two AGVs of one slot each that share every stop; blanks of two kinds, turned on the lathe
(irreversibly: a spoilt turn scraps the blank, a dead end once the spares of its kind are gone),
painted in the booth (a spoilt coat smudges the part, which must be stripped first), shipped at
the dock to fill an order of its kind; machines that must be switched on and, at the end, off;
declared resources for RCHPN; a dead-end test; a domain estimate for whole-problem planning.
"""

from __future__ import annotations

from typing import Any, Mapping

from nowplan.api import (
    Domain, Goal, Operator, Precondition, Predicate, Resource, ResourceModel, ResourceUse, Var, atom,
    exactly_one, excludes, static,
)

a, b, s, s2, o, k = (Var(x) for x in ("a", "b", "s", "s2", "o", "k"))
# top: what happens to each blank and which order it fills; below: where the parts and AGVs are;
# bottom: a free slot on the AGV, the machines' power, a clean surface
TASK, ROUTE, REACH = 3, 2, 1

PREDICATES = {x.name: x for x in (
    Predicate("agv_at", 2, ("agv", "station")),
    Predicate("carrying", 2, ("agv", "part")),
    Predicate("free", 1, ("agv",)),
    Predicate("at", 2, ("part", "station")),
    Predicate("raw", 1, ("part",)),
    Predicate("turned", 1, ("part",)),
    Predicate("painted", 1, ("part",)),
    Predicate("clean", 1, ("part",)),  # the surface takes paint (a spoilt coat smudges it)
    Predicate("shipped", 1, ("part",)),
    Predicate("scrapped", 1, ("part",)),  # no operator makes it: the world does, on a spoilt turn
    Predicate("open", 1, ("order",)),
    Predicate("filled", 1, ("order",)),
    Predicate("on", 1, ("station",)),  # a machine is powered
    # static
    Predicate("link", 2, ("station", "station")),  # both ways
    Predicate("lathe", 1, ("station",)),
    Predicate("booth", 1, ("station",)),
    Predicate("dock", 1, ("station",)),
    Predicate("machine", 1, ("station",)),
    Predicate("kind", 2, ("part", "kind")),
    Predicate("wants", 2, ("order", "kind")),
)}


def pre(name: str, *args: object, crit: int, value: bool = True) -> Precondition:
    return Precondition(atom(name, *args, value=value), crit)


SH, CO, CT = ResourceUse.SHAREABLE, ResourceUse.CONTAINED, ResourceUse.CONTINUAL

OPERATORS = (
    Operator("move", (a, s, s2),
             (pre("agv_at", a, s, crit=ROUTE), static(atom("link", s, s2))),
             (atom("agv_at", a, s2), atom("agv_at", a, s, value=False)),
             param_types=("agv", "station", "station"),
             resources=(Resource(("agv", a), SH), Resource(("stop", s2), SH))),
    Operator("load", (a, b, s),
             (pre("at", b, s, crit=TASK), pre("agv_at", a, s, crit=ROUTE), pre("free", a, crit=REACH)),
             (atom("carrying", a, b), atom("at", b, s, value=False), atom("free", a, value=False)),
             param_types=("agv", "part", "station"),
             resources=(Resource(("agv", a), CT), Resource(("stop", s), SH))),
    Operator("unload", (a, b, s),
             (pre("carrying", a, b, crit=TASK), pre("agv_at", a, s, crit=ROUTE)),
             (atom("at", b, s), atom("carrying", a, b, value=False), atom("free", a)),
             param_types=("agv", "part", "station"),
             resources=(Resource(("agv", a), CO), Resource(("stop", s), SH))),
    Operator("power_on", (s,), (static(atom("machine", s)),), (atom("on", s),), param_types=("station",)),
    Operator("power_off", (s,), (static(atom("machine", s)),), (atom("on", s, value=False),),
             param_types=("station",)),
    Operator("turn", (b, s),
             (pre("raw", b, crit=TASK), pre("at", b, s, crit=ROUTE), static(atom("lathe", s)),
              pre("on", s, crit=REACH)),
             (atom("turned", b), atom("raw", b, value=False)), cost=2.0,
             param_types=("part", "station"), resources=(Resource(("machine", s), CO),)),
    Operator("paint", (b, s),
             (pre("turned", b, crit=TASK), pre("at", b, s, crit=ROUTE), static(atom("booth", s)),
              pre("on", s, crit=REACH), pre("clean", b, crit=REACH)),
             (atom("painted", b),), cost=2.0,
             param_types=("part", "station"), resources=(Resource(("machine", s), CO),)),
    Operator("strip", (b, s),
             (pre("at", b, s, crit=ROUTE), static(atom("booth", s))),
             (atom("clean", b),), cost=2.0, param_types=("part", "station")),
    Operator("ship", (o, b, s, k),
             (pre("open", o, crit=TASK), pre("painted", b, crit=TASK), static(atom("kind", b, k)),
              static(atom("wants", o, k)), pre("at", b, s, crit=ROUTE), static(atom("dock", s))),
             (atom("filled", o), atom("open", o, value=False), atom("shipped", b), atom("at", b, s, value=False)),
             param_types=("order", "part", "station", "kind"), resources=(Resource(("dock", s), SH),)),
)

def _part(x: Any) -> Any:
    return x.args[1] if x.predicate == "carrying" else x.args[0]


CONFLICTS = (
    exactly_one("agv_at", key=0),
    exactly_one("at", "carrying", "shipped", "scrapped", key=_part),  # a part lies, rides, left or is scrap
    exactly_one("carrying", "free", key=0),  # an AGV carries one part or is free
    exactly_one("open", "filled", key=0),
    excludes(atom("raw", b), atom("turned", b)),
)


def dead_end(goal: Goal, belief: Any, levels: Any, objects: Mapping[str, str | None]) -> str | None:
    """No plan when some kind has fewer usable parts (lying or riding) than unfilled orders in the goal."""
    wants = {str(x): str(y) for (x, y) in belief.facts("wants")}
    need: dict[str, int] = {}
    for g in goal.atoms:
        if g.predicate == "filled" and g.value is True and not belief.value(("filled", g.args)):
            kk = wants.get(str(g.args[0]))
            if kk is not None:
                need[kk] = need.get(kk, 0) + 1
    if not need:
        return None
    usable = {str(x) for (x, _) in belief.facts("at")} | {str(x) for (_, x) in belief.facts("carrying")}
    have: dict[str, int] = {}
    for (p, kk) in belief.facts("kind"):
        if str(p) in usable:
            have[str(kk)] = have.get(str(kk), 0) + 1
    for kk, n in sorted(need.items()):
        if have.get(kk, 0) < n:
            return f"dead end: {n} order(s) of kind {kk} to fill and {have.get(kk, 0)} usable blank(s) of it left"
    return None


_WAS_ON: dict[int, frozenset[str]] = {}  # per belief object: the machines on when last asked


def tripped_machine(plan: Any, belief: Any) -> str | None:
    """Selective's trigger: a machine that was on is off now (a power trip) and the plan still works on it."""
    on = frozenset(str(x) for (x,) in belief.facts("on"))
    was = _WAS_ON.get(id(belief), on)
    _WAS_ON[id(belief)] = on
    lost = was - on
    for act in plan.actions:
        if act.name in ("turn", "paint") and str(act.args[1]) in lost:
            return f"machine {act.args[1]} tripped off"
    return None


DOMAIN = Domain("millshop", PREDICATES, OPERATORS,
                types={"agv": None, "station": None, "part": None, "order": None, "kind": None},
                conflicts=CONFLICTS, dead_end=dead_end, triggers=(tripped_machine,),
                resources=ResourceModel(orders={"ship": 1, "unload": 1, "load": 1}))
