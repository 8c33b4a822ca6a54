"""A delivery drone: fly between sampled poses, recharge at stations, localize with a noisy fix,
pick parcels up and drop them at the depot.  Every predicate is a test of the belief."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from nowplan.api import AtLeastRule, Atom, Domain, Generator, Operator, Precondition, Predicate, ToleranceRule, Var, atom, at_most_one, excludes

from drone_domain.belief import Pose, dist

p, frm, to, need, left, here = (Var(n) for n in ("p", "frm", "to", "need", "left", "here"))
# three classes: where the drone flies, the battery that takes and which parcels it carries (ROUTE:
# what decides whether a plan can work at all); its free hook (REACH); how well it knows where it is
# (SENSE: the top levels plan as if the position were known, the bottom one adds the looks)
ROUTE, REACH, SENSE = 3, 2, 1
TASK = ROUTE
NEAR = 0.25  # At(pose): the estimate lies within this of the pose
RATE = 0.1  # battery per unit flown
MARGIN = 0.01  # battery added to every leg (the true leg is longer than the believed one)
RESERVE = 0.12  # battery every flight but one to a charger lands with (for the legs gusts and misses add)
FLY_SIGMA = 0.6  # the spread a flight needs to start, and what it promises after (a loose tolerance)
FIX_SIGMA = 0.12  # what a localize promises
PICK_SIGMA = 0.2  # the spread a pick or a drop needs
DOCK_SIGMA = 0.3  # the spread docking on a charger needs
STATIONS: tuple[Pose, ...] = ((0.5, 0.5), (4.0, 4.0), (0.5, 7.5), (7.5, 0.5), (7.5, 7.5))  # one at the depot
DEPOT: Pose = (0.5, 0.5)
CREW_COST = 30.0


def t_at(b: Any, args: tuple[Any, ...], value: Any) -> bool:
    return (dist(b.pos, args[0]) <= NEAR) == bool(value)


def t_localized(b: Any, args: tuple[Any, ...], value: Any) -> bool:
    return bool(b.sigma <= float(value))


def t_battery(b: Any, args: tuple[Any, ...], value: Any) -> bool:
    return bool(b.battery >= float(value))


def t_holding(b: Any, args: tuple[Any, ...], value: Any) -> bool:
    return bool((b.held == args[0]) == bool(value))


def t_hand_empty(b: Any, args: tuple[Any, ...], value: Any) -> bool:
    return (b.held is None) == bool(value)


def t_delivered(b: Any, args: tuple[Any, ...], value: Any) -> bool:
    return (args[0] in b.delivered) == bool(value)


PREDICATES = {x.name: x for x in (
    Predicate("At", 1, test=t_at),
    Predicate("Localized", 0, rule=ToleranceRule(), test=t_localized, boolean=False),
    Predicate("Battery", 0, rule=AtLeastRule(), test=t_battery, boolean=False),
    Predicate("Holding", 1, ("parcel",), test=t_holding),
    Predicate("HandEmpty", 0, test=t_hand_empty),
    Predicate("Delivered", 1, ("parcel",), test=t_delivered),
)}


def leg(a: Pose, b: Pose) -> float:
    return round(RATE * dist(a, b) * 1.05 + MARGIN, 3)


def fly_from(bindings: Any, goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """Where to fly to ``to`` from: here, a charger, the depot or a parcel; the battery it needs is
    what the goal asks for on arrival plus the leg."""
    dest: Pose | None = bindings.get(to)
    if dest is None:  # another effect (the battery left) unified with the goal: no destination, no flight
        return
    want = goal.get(("Battery", ())) if goal is not None else None
    floor = 0.0 if dest in STATIONS else RESERVE  # a flight to a charger may land empty
    after = max(float(want.value), floor) if want is not None and want.value is not True else floor
    starts = [belief.pos] + list(STATIONS) + [DEPOT] + sorted(belief.parcels.values())
    seen: set[Pose] = set()
    for s in starts:
        s = (round(s[0], 2), round(s[1], 2))
        if s in seen or dist(s, dest) <= NEAR:
            continue
        seen.add(s)
        n = round(after + leg(s, dest), 3)
        if n <= 1.0:
            yield {frm: s, need: n, left: after}


def charger(bindings: Any, goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """The chargers, nearest first."""
    for s in sorted(STATIONS, key=lambda s: dist(s, belief.pos)):
        yield {here: s}


def parcel_pose(bindings: Any, goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """Where the parcel lies, as the dispatcher reports it."""
    where = belief.parcels.get(bindings.get(p))  # (no parcel bound: another effect unified; nothing)
    if where is not None:
        yield {here: where}


def depot(bindings: Any, goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    yield {here: DEPOT}


def fly_cost(bindings: Any, belief: Any) -> float:
    return 0.5 + dist(bindings[frm], bindings[to])


def pre(a: Atom, crit: int) -> Precondition:
    return Precondition(a, crit)


OPERATORS = (
    Operator("fly", (frm, to, need, left),
             (pre(atom("At", frm), ROUTE), pre(atom("Battery", value=need), ROUTE),
              pre(atom("Localized", value=FLY_SIGMA), SENSE)),
             (atom("At", to), atom("Battery", value=left), atom("Localized", value=FLY_SIGMA)),
             cost=fly_cost, generators=(Generator("fly_from", (frm, need, left), fly_from, (to,)),)),
    Operator("charge", (here,), (pre(atom("At", here), ROUTE), pre(atom("Localized", value=DOCK_SIGMA), SENSE)),
             (atom("Battery", value=1.0),), cost=2.0,
             generators=(Generator("charger", (here,), charger),)),
    # stranded: a ground crew brings a fresh battery wherever the drone is (dear, but always there)
    Operator("call_crew", (), (), (atom("Battery", value=1.0),), cost=CREW_COST),
    Operator("localize", (), (), (atom("Localized", value=FIX_SIGMA),)),
    Operator("pick", (p, here),
             (pre(atom("Delivered", p, value=False), TASK), pre(atom("At", here), ROUTE),
              pre(atom("HandEmpty"), REACH), pre(atom("Localized", value=PICK_SIGMA), SENSE)),
             (atom("Holding", p), atom("HandEmpty", value=False)), param_types=("parcel", None),
             generators=(Generator("parcel_pose", (here,), parcel_pose, (p,)),)),
    Operator("drop", (p, here),
             (pre(atom("Holding", p), TASK), pre(atom("At", here), ROUTE),
              pre(atom("Localized", value=PICK_SIGMA), SENSE)),
             (atom("Delivered", p), atom("Holding", p, value=False), atom("HandEmpty")),
             param_types=("parcel", None), generators=(Generator("depot", (here,), depot),)),
)


def far_apart(a: Atom, b: Atom) -> bool:
    """The drone is not at two poses further apart than twice the tolerance."""
    return (a.predicate == b.predicate == "At" and a.value is True and b.value is True
            and dist(pose_of(a), pose_of(b)) > 2 * NEAR)


def pose_of(a: Atom) -> Pose:
    pose: Any = a.args[0]
    return (float(pose[0]), float(pose[1]))


CONFLICTS = (
    far_apart,
    at_most_one("Holding", key=()),
    excludes(atom("HandEmpty"), atom("Holding", p)),
)

DOMAIN = Domain("drone", PREDICATES, OPERATORS, types={"parcel": None}, conflicts=CONFLICTS)
