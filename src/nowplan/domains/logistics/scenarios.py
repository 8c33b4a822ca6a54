"""Seeded logistics problems and the simulated world they run in."""

from __future__ import annotations

import random
from functools import partial
from dataclasses import dataclass

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Atom, Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.state import State
from nowplan.domains.logistics.model import DOMAIN
from nowplan.domains.registry import Episode
from nowplan.worlds.symbolic import SymbolicWorld


@dataclass(frozen=True)
class Size:
    cities: int
    places: int  # locations per city, one of them the airport
    trucks_per_city: int
    airplanes: int
    packages: int


SIZES = {
    "tiny": Size(1, 3, 1, 0, 2),
    "small": Size(2, 3, 1, 1, 3),
    "medium": Size(3, 3, 1, 1, 5),
    "large": Size(4, 4, 1, 2, 8),
}


def generate(size: Size, seed: int, name: str = "logistics") -> Problem:
    """A random problem: packages start and end at random places, vehicles placed at random."""
    if size.cities < 1 or size.places < 1 or size.packages < 0:
        raise ValueError("need at least one city and one place per city")
    if size.cities > 1 and size.airplanes < 1:
        raise ValueError("several cities need at least one airplane")
    rng = random.Random(seed)
    objects: dict[str, str | None] = {}
    facts: list[Atom] = []
    places: list[str] = []
    airports: list[str] = []
    for ci in range(size.cities):
        city = f"c{ci}"
        objects[city] = "city"
        for li in range(size.places):
            loc = f"c{ci}-l{li}"
            objects[loc] = "location"
            places.append(loc)
            facts.append(atom("in_city", loc, city))
            if li == 0:
                airports.append(loc)
                facts.append(atom("airport", loc))
        for ti in range(size.trucks_per_city):
            truck = f"truck{ci}" + (f"-{ti}" if size.trucks_per_city > 1 else "")
            objects[truck] = "truck"
            facts.append(atom("serves", truck, city))
            facts.append(atom("at", truck, f"c{ci}-l{rng.randrange(size.places)}"))
    for ai in range(size.airplanes):
        plane = f"plane{ai}"
        objects[plane] = "airplane"
        facts.append(atom("at", plane, rng.choice(airports)))
    goal: list[Atom] = []
    for pi in range(size.packages):
        pkg = f"p{pi}"
        objects[pkg] = "package"
        start = rng.choice(places)
        end = rng.choice([x for x in places if x != start] or places)
        facts.append(atom("at", pkg, start))
        goal.append(atom("at", pkg, end))
    return Problem(DOMAIN, objects, State(facts), Goal.of(goal, DOMAIN.rules), f"{name}-s{seed}")


def move_a_package(packages: frozenset[str], state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: somebody carries a package lying at a place to another place of its city."""
    lying = sorted((args[0], args[1]) for args in state.facts("at") if args[0] in packages)
    if not lying:
        return []
    pkg, loc = rng.choice(lying)
    city = next(a[1] for a in state.facts("in_city") if a[0] == loc)
    others = sorted((a[0] for a in state.facts("in_city") if a[1] == city and a[0] != loc), key=str)
    if not others:
        return []
    return [atom("at", pkg, loc, value=False), atom("at", pkg, rng.choice(others))]


def episode(size_name: str, seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0) -> Episode:
    prob = generate(SIZES[size_name], seed, f"logistics-{size_name}")
    packages = frozenset(o for o, t in prob.objects.items() if t == "package")
    world = SymbolicWorld(
        DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
        exogenous=partial(move_a_package, packages), exogenous_prob=exogenous_prob,
    )
    faults = [f"{name} p={p:g}" for name, p in (("failure", failure_prob), ("exogenous", exogenous_prob)) if p]
    desc = ", ".join([f"{size_name} logistics", *faults])
    return Episode(prob, world, SymbolicBelief(prob.init), desc)
