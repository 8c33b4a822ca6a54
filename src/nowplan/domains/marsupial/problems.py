"""Seeded marsupial logistics problems (seed 002 V-B) and the seed's FF instance.

A problem has 5 cities, each an airport with 4 locations whose roads follow
a layout drawn at random: *circular* (a ring through the airport and the
locations), *radial* (every location joined to the airport only),
*linear* (the ring with one road missing) or *connected* (every pair
joined).  One truck serves each city and one plane flies between the
airports; every vehicle's cargo area is 3×6 or 4×8 at random.  Packages
(3–10) have one of six shapes.  The four *regimes* vary how many places
packages start from and go to: ``single`` (one origin, one destination),
``origins`` (origins spread over every location, one destination),
``dests`` (one origin, destinations spread) and ``both`` (both spread).
"""

from __future__ import annotations

import itertools
import random
from dataclasses import dataclass, field

from nowplan.core.atoms import Atom, Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.state import State
from nowplan.domains.marsupial.grid import NONE, SHAPES, SIZES, Hold
from nowplan.domains.marsupial.model import make_domain
from nowplan.errors import ScenarioError

LAYOUTS = ("circular", "radial", "linear", "connected")
REGIMES = {
    "single": "single origin, single destination",
    "origins": "dispersed origins, single destination",
    "dests": "single origin, dispersed destinations",
    "both": "dispersed origins and destinations",
}


@dataclass(frozen=True)
class City:
    name: str
    airport: str
    places: tuple[str, ...]  # the airport first
    layout: str
    roads: tuple[tuple[str, str], ...]


@dataclass(frozen=True)
class MapSpec:
    """The static part of a problem, kept for rendering and reports."""

    cities: tuple[City, ...]
    trucks: dict[str, str] = field(hash=False)  # truck -> city
    bays: dict[str, tuple[int, int]] = field(hash=False)  # vehicle -> (rows, cols)
    plane: str = "plane"


def roads(places: tuple[str, ...], layout: str, rng: random.Random) -> tuple[tuple[str, str], ...]:
    ring = [(places[i], places[(i + 1) % len(places)]) for i in range(len(places))]
    if layout == "circular":
        return tuple(ring)
    if layout == "linear":
        drop = rng.randrange(len(ring))
        return tuple(r for i, r in enumerate(ring) if i != drop)
    if layout == "radial":
        return tuple((places[0], q) for q in places[1:])
    if layout == "connected":
        return tuple(itertools.combinations(places, 2))
    raise ScenarioError(f"unknown layout '{layout}'; valid layouts: {', '.join(LAYOUTS)}")


def make_map(
    rng: random.Random, n_cities: int = 5, per_city: int = 4, layouts: tuple[str, ...] = LAYOUTS,
    sizes: tuple[tuple[int, int], ...] = SIZES,
) -> MapSpec:
    cities = []
    trucks: dict[str, str] = {}
    bays: dict[str, tuple[int, int]] = {}
    for ci in range(n_cities):
        name = f"c{ci}"
        places = (f"{name}-ap", *(f"{name}-l{j}" for j in range(per_city)))
        layout = rng.choice(layouts)
        cities.append(City(name, places[0], places, layout, roads(places, layout, rng)))
        trucks[f"truck{ci}"] = name
        bays[f"truck{ci}"] = rng.choice(sizes)
    bays["plane"] = rng.choice(sizes)
    return MapSpec(tuple(cities), trucks, bays)


def problem_from(
    spec: MapSpec, rng: random.Random, cargo: list[tuple[str, str, str]], name: str
) -> Problem:
    """``cargo`` = ``[(shape, origin, destination)]``; vehicles start at random places."""
    objects: dict[str, str | None] = {}
    facts: list[Atom] = []
    reach: dict[str, frozenset[str]] = {}
    by_city = {c.name: c for c in spec.cities}
    for c in spec.cities:
        for q in c.places:
            objects[q] = "location"
    for truck, cname in spec.trucks.items():
        c = by_city[cname]
        objects[truck] = "truck"
        reach[truck] = frozenset(c.places)
        facts += [atom("reachable", q, truck) for q in c.places]
        for x, y in c.roads:
            facts += [atom("connected", x, y, truck), atom("connected", y, x, truck)]
        facts.append(atom("at", truck, rng.choice(c.places)))
    airports = [c.airport for c in spec.cities]
    objects[spec.plane] = "plane"
    reach[spec.plane] = frozenset(airports)
    facts += [atom("reachable", q, spec.plane) for q in airports]
    facts += [atom("connected", x, y, spec.plane) for x in airports for y in airports if x != y]
    facts.append(atom("at", spec.plane, rng.choice(airports)))
    for veh, (rows, cols) in spec.bays.items():
        facts += [atom("cargo", veh, value=Hold.empty(rows, cols)), atom("door", veh, value=NONE),
                  atom("packed", veh)]
    goal = []
    for i, (shape, origin, dest) in enumerate(cargo):
        pkg = f"p{i}"
        objects[pkg] = "package"
        facts += [atom("shape", pkg, shape), atom("at", pkg, origin)]
        goal.append(atom("at", pkg, dest))
    domain = make_domain(reach)
    return Problem(domain, objects, State(facts), Goal.of(goal, domain.rules), name)


def generate(regime: str, n_packages: int, seed: int) -> tuple[Problem, MapSpec]:
    """A random problem of ``regime`` with ``n_packages`` packages (seed 002 V-B)."""
    if regime not in REGIMES:
        raise ScenarioError(f"unknown regime '{regime}'; valid regimes: {', '.join(REGIMES)}")
    if n_packages < 1:
        raise ScenarioError("a problem needs at least one package")
    rng = random.Random(f"marsupial/{regime}/{n_packages}/{seed}")
    spec = make_map(rng)
    places = [q for c in spec.cities for q in c.places]
    origin = rng.choice(places)
    dest = rng.choice([q for q in places if q != origin])
    cargo = []
    for _ in range(n_packages):
        o = rng.choice(places) if regime in ("origins", "both") else origin
        d = rng.choice(places) if regime in ("dests", "both") else dest
        while d == o:
            o = rng.choice(places) if regime in ("origins", "both") else o
            d = rng.choice(places) if regime in ("dests", "both") else d
        cargo.append((rng.choice(sorted(SHAPES)), o, d))
    prob = problem_from(spec, rng, cargo, f"marsupial-{regime}-{n_packages}-s{seed}")
    return prob, spec


def ff_instance(seed: int = 0) -> tuple[Problem, MapSpec]:
    """Seed 002 V-B's FF instance: 8 locations, 2 airports, a one-cell package to the far airport."""
    rng = random.Random(f"marsupial/ff/{seed}")
    spec = make_map(rng, n_cities=2, per_city=3, layouts=("circular",), sizes=((3, 6),))
    start = rng.choice(spec.cities[0].places[1:])
    prob = problem_from(spec, rng, [("dot", start, spec.cities[1].airport)], f"marsupial-ff-s{seed}")
    return prob, spec
