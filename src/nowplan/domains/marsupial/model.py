"""The marsupial logistics domain (seed 002 V-A and appendix) in the core language.

Fluents: ``at(x, l)`` (a package on the ground or a vehicle at a location),
``in(p, v)``, the derived ``same_city(p, v)`` (a test: ``p`` is in ``v`` or
lies at a location ``v`` reaches), and per vehicle ``door(v)`` (what is in
its load region: ``none``, a package ready to unload, or ``busy``),
``cargo(v)`` (the whole cargo bay, a :class:`~.grid.Hold`) and ``packed(v)``.

Criticalities (a precondition is kept at level ``i`` when its criticality is
above ``i``; the top level is 4):

====  =========================================================================
 5    where packages are: ``same_city(p, v)`` for Unload, ``at(p, l)`` for Load
      and SameCity; static facts; a Travel's start; the exact bay for robot
      operators and Pack
 4    ``in(p, v)`` for Unload
 3    ``at(v, l)`` for Load and Unload: where vehicles must be
 2    ``door(v)`` for Load (free) and Unload (the package), ``packed(v)`` for Travel
====  =========================================================================

So the top level plans each package's route as Unloads and SameCity
inferences (a truck to its airport, the plane, a truck to the destination);
the next level adds the Loads; then the Travels; the last one the loader's
work in the cargo bay, which a generator plans with A* over the grid
(:mod:`.loader`).  Load and SameCity choose their location in the now
(:class:`Where`), which also keeps the planner from refining a step by
"teleporting" a package with a cheaper abstract Unload instance.  Costs:
vehicle operators 10, robot operators 1, inference operators 0.  Resources
(seed 002 III-C, V-B): Load and Unload use their vehicle and its stop
(shareable) and the vehicle's space — continually for a Load (the package
takes room as long as it is in), contained for an Unload (room is given
back); the domain's test makes vehicle and space shareable whenever the
greedy packer fits everything, so loads are combined while they fit and an
unload goes before a load that would not fit.  Robot operators use the
loader and the load region.

The planner settings for this domain are :data:`PLANNER` (LM-cut explored
on demand over the generators' values, see :mod:`nowplan.planning.relaxed`).
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from functools import lru_cache
from typing import Any

from nowplan.acting.resources import ResourceModel
from nowplan.core.atoms import AtMostOne, Atom, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.operators import (
    Action, Generator, Operator, Precondition, Resource, ResourceUse, reads_nothing,
)
from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.bay_relaxed import fetch_infeasible
from nowplan.domains.marsupial.dead_ends import buried_package
from nowplan.domains.marsupial.small_plans import small_plan
from nowplan.domains.marsupial.grid import NONE, Door, Hold, can_share, door_package, is_packed
from nowplan.planning.regression import PlannerConfig

NAME = "marsupial"
# planner settings for this domain: LM-cut over the achievers the grounder finds (generators and the
# same_city test included; a few hundred nodes per search up to 20 packages, so the shortcuts' budget is
# 20 000, the largest solved search seen being 308); the time limit counts CPU seconds, so a joint
# search of combined subgoals ends alike on a loaded machine
PLANNER = PlannerConfig(shortcut_nodes=20_000, time_limit=120.0, clock="cpu", heuristic="lmcut",
                        lazy_relaxation=True)
VEHICLE_COST, ROBOT_COST, INFERENCE_COST = 10.0, 1.0, 0.0
PKG, IN, VEH, BAY = 5, 4, 3, 2  # criticality classes (see the module docstring)

p, v, l, a, b = (Var(n) for n in ("p", "v", "l", "a", "b"))
L1, L2, D1, D2, C, L = (Var(n) for n in ("L1", "L2", "d1", "d2", "c", "L"))
SH, CT, CN = ResourceUse.SHAREABLE, ResourceUse.CONTAINED, ResourceUse.CONTINUAL

TYPES = {"package": None, "vehicle": None, "truck": "vehicle", "plane": "vehicle", "location": None}


def _pre(x: Atom, crit: int) -> Precondition:
    return Precondition(x, crit)


# -- the derived fluent ------------------------------------------------------------------


class _ByFirst:
    """A belief's facts of one predicate by their first argument, rebuilt only when its list changes.

    A belief over an immutable state hands back the same list while the state
    stands, so the test and the generators below look one object up instead of
    scanning every package's fact (which made each test cost grow with the
    number of packages); a belief that makes a new list each time gets a new index.
    """

    __slots__ = ("predicate", "_facts", "_by")

    def __init__(self, predicate: str) -> None:
        self.predicate = predicate
        self._facts: Any = None
        self._by: dict[Any, list[tuple[Any, ...]]] = {}

    def __call__(self, belief: Any) -> dict[Any, list[tuple[Any, ...]]]:
        facts = belief.facts(self.predicate)
        if facts is not self._facts:
            by: dict[Any, list[tuple[Any, ...]]] = {}
            for args in facts:
                if args:
                    by.setdefault(args[0], []).append(args)
            self._facts, self._by = facts, by
        return self._by


_AT, _IN = _ByFirst("at"), _ByFirst("in")


def same_city_holds(belief: Any, args: tuple[Any, ...], value: Any) -> bool:
    """``same_city(p, v)``: ``p`` is inside ``v`` or on the ground where ``v`` can go."""
    pkg, veh = args
    truth = bool(belief.value(("in", (pkg, veh))))
    if not truth:
        truth = any(belief.value(("reachable", (x[1], veh))) for x in _AT(belief).get(pkg, ()))
    return truth == bool(value)


# -- generators: the bay's configuration from the robot's motion planner -------------------------


def _bay(belief: Any, veh: str) -> lp.Config:
    hold = belief.value(("cargo", (veh,)))
    shapes = dict(belief.facts("shape"))
    return hold, lp.door_of(str(belief.value(("door", (veh,)))), shapes)


def _transition(kind: str, goal: Any, belief: Any, veh: str) -> lp.Transition | None:
    """The last robot operator towards what ``goal`` asks of ``veh``'s bay, from the belief."""
    start = _bay(belief, veh)
    want_cargo = goal.get(("cargo", (veh,)))
    want_door = goal.get(("door", (veh,)))
    t: lp.Transition | None = None
    if want_cargo is not None:
        status = str(want_door.value) if want_door is not None else None
        t = lp.CACHE.into(start, want_cargo.value, status)
    elif want_door is not None:
        target = str(want_door.value)
        pkg = door_package(target)
        if target == NONE:
            path = lp.CACHE.path(start, "stow", lp.stow_goal, lp.stow_h)
        elif pkg is not None and pkg == target:
            path = lp.CACHE.path(start, f"fetch:{pkg}", lp.fetch_goal(pkg), lp.fetch_h(pkg),
                                 infeasible=lambda c: fetch_infeasible(c[0], c[1], pkg))
        else:
            path = None
        t = path[-1] if path else None
    if t is None or t.kind != kind:
        return None
    return t


def _robot_gen(kind: str, arg: Var) -> Generator:
    def fn(bind: Mapping[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
        veh = bind.get(v)
        if veh is None or isinstance(veh, Var):
            return
        t = _transition(kind, goal, belief, str(veh))
        if t is not None:
            yield {arg: t.arg, L1: t.before[0], L2: t.after[0], D1: t.door_before, D2: t.door_after}

    return Generator(f"loader_{kind}", (arg, L1, L2, D1, D2), fn, (v,), reads=_bay_wanted)


def _bay_wanted(bind: Mapping[Var, Any], goal: Any) -> tuple[Any, Any]:
    """What a robot generator reads of the goal: the cargo and door it asks of the vehicle."""
    veh = bind.get(v)
    return goal.get(("cargo", (veh,))), goal.get(("door", (veh,)))


def _pack_gen(bind: Mapping[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    veh = bind.get(v)
    if veh is None or isinstance(veh, Var):
        return
    start = _bay(belief, str(veh))
    if is_packed(*start):
        yield {L: start[0]}
        return
    path = lp.CACHE.path(start, "stow", lp.stow_goal, lp.stow_h)
    if path:
        yield {L: path[-1].after[0]}


# -- operators -------------------------------------------------------------------------------


def _robot(name: str, arg: Var, arg_type: str | None) -> Operator:
    return Operator(
        name, (v, arg, L1, L2, D1, D2),
        (_pre(atom("cargo", v, value=L1), PKG), _pre(atom("door", v, value=D1), PKG)),
        (atom("cargo", v, value=L2), atom("door", v, value=D2), atom("packed", v, value=False)),
        cost=ROBOT_COST, param_types=("vehicle", arg_type, None, None, None, None),
        resources=(Resource(("loader", v), CT), Resource(("load_region", v), CT)),
        generators=(_robot_gen(name.split("_", 1)[1], arg),),
    )


def operators(where: Where) -> tuple[Operator, ...]:
    """The operators; Load and SameCity choose their location with ``where`` (in the now)."""
    return (
        Operator(
            "load", (p, v, l),
            (_pre(atom("reachable", l, v), PKG), _pre(atom("at", p, l), PKG), _pre(atom("at", v, l), VEH),
             _pre(atom("door", v, value=NONE), BAY)),
            (atom("in", p, v), atom("at", p, l, value=False), atom("door", v, value=p),
             atom("packed", v, value=False)),
            cost=VEHICLE_COST, param_types=("package", "vehicle", "location"),
            resources=(Resource(("vehicle", v), SH), Resource(("stop", v, l), SH), Resource(("space", v), CN)),
            generators=(Generator("load_place", (l,), where.load_place, (p, v), reads=where.wanted),),
        ),
        Operator(
            "unload", (p, v, l),
            (_pre(atom("reachable", l, v), PKG), _pre(atom("same_city", p, v), PKG), _pre(atom("in", p, v), IN),
             _pre(atom("at", v, l), VEH), _pre(atom("door", v, value=p), BAY)),
            (atom("at", p, l), atom("in", p, v, value=False), atom("door", v, value=NONE)),
            cost=VEHICLE_COST, param_types=("package", "vehicle", "location"),
            resources=(Resource(("vehicle", v), SH), Resource(("stop", v, l), SH), Resource(("space", v), CT)),
        ),
        Operator(
            "travel", (v, a, b),
            (_pre(atom("connected", a, b, v), PKG), _pre(atom("at", v, a), PKG), _pre(atom("packed", v), BAY)),
            (atom("at", v, b), atom("at", v, a, value=False)),
            cost=VEHICLE_COST, param_types=("vehicle", "location", "location"),
            resources=(Resource(("vehicle", v), SH), Resource(("stop", v, b), SH)),
        ),
        _robot("loader_move", C, None),
        _robot("loader_grasp", p, "package"),
        _robot("loader_place", p, "package"),
        Operator(
            "same_city", (p, v, l),
            (_pre(atom("reachable", l, v), PKG), _pre(atom("at", p, l), PKG)),
            (atom("same_city", p, v),),
            cost=INFERENCE_COST, param_types=("package", "vehicle", "location"),
            generators=(Generator("same_city_place", (l,), where.same_city_place, (p, v), reads=where.wanted),),
        ),
        Operator(
            "pack", (v, L),
            (_pre(atom("cargo", v, value=L), PKG), _pre(atom("door", v, value=NONE), PKG)),
            (atom("packed", v),),
            cost=INFERENCE_COST, param_types=("vehicle", None),
            resources=(Resource(("storage", v), CT),),
            generators=(Generator("pack", (L,), _pack_gen, (v,), reads=reads_nothing),),
        ),
    )

PREDICATES = {
    "at": Predicate("at", 2, (None, "location")),
    "in": Predicate("in", 2, ("package", "vehicle")),
    "same_city": Predicate("same_city", 2, ("package", "vehicle"), test=same_city_holds),
    "reachable": Predicate("reachable", 2, ("location", "vehicle")),
    "connected": Predicate("connected", 3, ("location", "location", "vehicle")),
    "shape": Predicate("shape", 2, ("package", None)),
    "door": Predicate("door", 1, ("vehicle",), boolean=False),
    "cargo": Predicate("cargo", 1, ("vehicle",), boolean=False),
    "packed": Predicate("packed", 1, ("vehicle",)),
}


class Where:
    """The "choose" of Load and SameCity (seed 002 appendix), decided in the now.

    A package is loaded where it lies if the vehicle can go there; otherwise
    it must pass through an airport: the vehicle's own for a truck, the one
    of the package's present city for the plane.  This keeps the abstract
    search to one location per Load instead of every place of the city.
    """

    def __init__(self, reach: Mapping[str, frozenset[str]], plane: str) -> None:
        self.reach = reach
        self.plane = plane
        airports = reach.get(plane, frozenset())
        self.airport_of: dict[str, str] = {}
        for veh, places in reach.items():
            if veh != plane:
                ap = next((x for x in places if x in airports), None)
                for x in places:
                    if ap is not None:
                        self.airport_of[x] = ap

    def place_now(self, belief: Any, pkg: str) -> str | None:
        """Where the package is (or the place of the vehicle carrying it)."""
        for args in _AT(belief).get(pkg, ()):
            return str(args[1])
        for args in _IN(belief).get(pkg, ()):
            return self.place_now(belief, str(args[1]))
        return None

    def wanted(self, bind: Mapping[Var, Any], goal: Any) -> tuple[str, ...]:
        """All that ``choose`` reads of the goal: where it wants the package, among ``v``'s places."""
        return tuple(sorted(self._wanted(str(bind.get(p)), str(bind.get(v)), goal)))

    def _wanted(self, pkg: str, veh: str, goal: Any) -> list[str]:
        reach = self.reach.get(veh, frozenset())
        return [str(a.args[1]) for a in goal.with_first("at", pkg) if a.value is True and a.args[1] in reach]

    def choose(self, pkg: str, veh: str, goal: Any, belief: Any) -> list[str]:
        reach = self.reach.get(veh, frozenset())
        wanted = self._wanted(pkg, veh, goal)
        if wanted:
            return wanted
        now = self.place_now(belief, pkg)
        if now is None:
            return sorted(reach)
        if now in reach:
            return [now]
        if veh == self.plane:
            return [self.airport_of[now]] if now in self.airport_of else sorted(reach)
        return sorted(x for x in reach if x in self.reach.get(self.plane, frozenset()))

    def load_place(self, bind: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any) -> Iterator[dict[Var, Any]]:
        pkg, veh = bind.get(p), bind.get(v)
        if pkg is None or veh is None or isinstance(pkg, Var) or isinstance(veh, Var):
            return
        now = self.place_now(belief, str(pkg))
        reach = self.reach.get(str(veh), frozenset())
        places = [now] if now in reach else self.choose(str(pkg), str(veh), goal, belief)
        for x in places:
            yield {l: x}

    def same_city_place(
        self, bind: Mapping[Var, Any], goal: Any, belief: Any, ctx: Any
    ) -> Iterator[dict[Var, Any]]:
        pkg, veh = bind.get(p), bind.get(v)
        if pkg is None or veh is None or isinstance(pkg, Var) or isinstance(veh, Var):
            return
        for x in self.choose(str(pkg), str(veh), goal, belief):
            yield {l: x}


class CityRule:
    """``same_city(p, v)`` is false once ``p`` is in another vehicle or where ``v`` cannot go.

    A keyed conflict rule (``group_keys``): atoms sharing a key cannot hold
    together, so goals are checked in linear time.
    """

    def __init__(self, reach: Mapping[str, frozenset[str]]) -> None:
        self.reach = reach
        self.vehicles = tuple(sorted(reach))
        self._keys: dict[Atom, list[Any]] = {}  # per atom: the planner asks at every node

    def group_keys(self, a: Atom) -> list[Any]:
        keys = self._keys.get(a)
        if keys is None:
            keys = self._keys[a] = self._group_keys(a)
        return keys

    def _group_keys(self, a: Atom) -> list[Any]:
        if a.value is not True or not a.args or a.args[0] in self.reach:
            return []
        pkg = a.args[0]
        if a.predicate == "same_city":
            return [("city", pkg, a.args[1])]
        if a.predicate == "in":
            return [("city", pkg, w) for w in self.vehicles if w != a.args[1]]
        if a.predicate == "at":
            return [("city", pkg, w) for w in self.vehicles if a.args[1] not in self.reach[w]]
        return []

    def __call__(self, a: Atom, b: Atom) -> bool:
        if a == b:
            return False
        ka = set(self.group_keys(a))
        return bool(ka) and any(k in ka for k in self.group_keys(b))


def make_domain(reach: Mapping[str, frozenset[str]], plane: str = "plane") -> Domain:
    """The domain for one map: ``reach[v]`` are the locations vehicle ``v`` can visit."""

    conflicts = (AtMostOne(("at", "in")), CityRule(reach))
    return Domain(NAME, PREDICATES, operators(Where(reach, plane)), TYPES, conflicts=conflicts,
                  unsupported=UNSUPPORTED, resources=RESOURCES, dead_end=buried_package)


_FLAT_WHY = (
    "the loader's work in a cargo bay is planned in the now by A* from the bay's current state "
    "(seed 002 appendix), so a plan that is flat {how} cannot bind it ahead; for flat planners "
    "export the instance to PDDL (benchmarks/marsupial_flat.py)"
)
UNSUPPORTED = {
    "flat": _FLAT_WHY.format(how="from the start"),
    **{s: _FLAT_WHY.format(how="(seed 004's online policy plans flat)")
       for s in ("online", "reuse", "deferred")},
}


# -- the ordering preference's resources ---------------------------------------------------------


def _packages_for(veh: str, actions: tuple[Action, ...] | list[Action]) -> list[str]:
    """The packages the actions load into or unload from ``veh``, in the actions' order."""
    out: list[str] = []
    for x in actions:
        if x.name in ("load", "unload") and x.args[1] == veh and str(x.args[0]) not in out:
            out.append(str(x.args[0]))
    return out


def vehicle_shareable(resource: tuple[Any, ...], first: Any, second: Any, belief: Any) -> bool | None:
    """A vehicle (and its space) is shareable by two subgoals if everything they move in it can be packed.

    Seed 002 V-B's greedy packer answers first (room for every package, as
    far back as possible); when it finds room, the loader's own stow search
    must also manage to put the packages away one after the other, as the
    loads will bring them (:func:`.loader.can_stow_in_turn`): a fit only
    the packer could find would leave a package at the door that no plan
    can stow, so the vehicle could not travel.

    The packer keeps the packages already in storage where they are, but the
    loader may move them: when the packer finds no room around them, yet
    every package (those aboard and the new ones) fits an empty bay, the
    loader's stow search decides.  Without that, unloads of packages that
    are all aboard already (the last one still at the door) were judged
    unshareable whenever the earlier loads had left the storage fragmented,
    and were refined one at a time, the first one dug out of a bay not yet
    packed.
    """
    if resource[0] not in ("vehicle", "space"):
        return None
    veh = str(resource[1])
    hold, door = _bay(belief, veh)
    if not isinstance(hold, Hold):
        return None
    shapes = dict(belief.facts("shape"))
    order = tuple((x, shapes[x]) for x in _packages_for(veh, [*first, *second]) if x in shapes)
    return _bay_shareable(hold, door, order)


@lru_cache(maxsize=1024)
def _bay_shareable(hold: Hold, door: Door, order: tuple[tuple[str, str], ...]) -> bool:
    """The verdict of :func:`vehicle_shareable` for a bay and the packages to load in this order
    (a function of those alone, memoised: ``arrange`` asks it for the vehicle and again for its
    space, and SelectGap, SelectParallelOps and Gather ask it again for the same pairs)."""
    extra = dict(order)
    if not can_share(hold, door, extra) and not _fits_repacked(hold, door, extra):
        return False
    return lp.can_stow_in_turn(hold, door, list(order))


def _fits_repacked(hold: Hold, door: Any, extra: Mapping[str, str]) -> bool:
    """Would the packer fit everything aboard and ``extra`` into the bay emptied (nothing fixed)?"""
    aboard = {n: s for n, s, _ in hold.items}
    if door is not None:
        aboard[door[0]] = door[1]
    if hold.held is not None and hold.held_shape is not None:
        aboard[hold.held] = hold.held_shape
    return can_share(Hold.empty(hold.rows, hold.cols), None, {**extra, **aboard})


def effort_bound(unmet: Sequence[Atom], belief: Any) -> float:
    """A lower bound on the cost of any plan achieving ``unmet`` (the peephole's effort estimates).

    ``door(v) = p`` for a package ``p`` in ``v``'s bay: a plan of robot operators (the zero-cost
    inferences leave the bay alone) costs at least the loader's consistent fetch estimate from
    the bay as it is, and any other plan has a vehicle operator (load or unload); every other
    atom is bounded by 0.  The estimator's small plan for an Unload's ``door`` precondition is a
    bay search, so a step this bound already shows to be no easier to reach than the one before
    it is not searched for (:func:`nowplan.acting.arrange.arrange`).
    """
    out = 0.0
    for x in unmet:
        if x.predicate != "door" or not isinstance(x.value, str) or door_package(x.value) != x.value:
            continue
        veh = str(x.args[0])
        hold, door = _bay(belief, veh)
        if not isinstance(hold, Hold):
            continue
        if x.value in hold.packages() or (door is not None and door[0] == x.value):
            out = max(out, min(lp.fetch_h(x.value)((hold, door)), VEHICLE_COST))
    return out


RESOURCES = ResourceModel(  # every marsupial domain carries it (make_domain)
    orders={"load": 1, "same_city": 1, "unload": 1},
    arrangeable=frozenset({"load", "unload", "same_city"}),
    shareable=vehicle_shareable,
    effort_bound=effort_bound,
    small_plan=small_plan,
)
