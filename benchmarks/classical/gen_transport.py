"""Problem generators for the transport-like domains.

logistics, depots, driverlog, gripper, miconic, no-mystery, zenotravel: one
plain function per domain returning the PDDL problem text; the same
arguments (``seed`` included) always give the same text.
"""

from __future__ import annotations

import random

from benchmarks.classical.problem import connected_graph, distances, fact, problem_text, towers


def _other(rng: random.Random, options: list[str], not_this: str) -> str:
    return rng.choice([o for o in options if o != not_this])


def logistics(cities: int = 2, places: int = 2, airplanes: int = 1, packages: int = 4, seed: int = 0) -> str:
    """IPC-2000 style: ``places`` per city (the first an airport), one truck per city."""
    rng = random.Random(seed)
    city = [f"city{c}" for c in range(1, cities + 1)]
    apt = [f"apt{c}" for c in range(1, cities + 1)]
    loc = {c: [f"pos{c}-{j}" for j in range(1, places)] for c in range(1, cities + 1)}
    allplaces = {c: [apt[c - 1], *loc[c]] for c in range(1, cities + 1)}
    flat = [p for c in range(1, cities + 1) for p in allplaces[c]]
    trucks = [f"tru{c}" for c in range(1, cities + 1)]
    planes = [f"apn{a}" for a in range(1, airplanes + 1)]
    pkgs = [f"obj{k}" for k in range(1, packages + 1)]
    init = [fact("in-city", p, city[c - 1]) for c in range(1, cities + 1) for p in allplaces[c]]
    init += [fact("at", trucks[c - 1], rng.choice(allplaces[c])) for c in range(1, cities + 1)]
    init += [fact("at", a, rng.choice(apt)) for a in planes]
    goal = []
    for k in pkgs:
        start = rng.choice(flat)
        init.append(fact("at", k, start))
        goal.append(fact("at", k, _other(rng, flat, start)))
    objects = [(city, "city"), (apt, "airport"), ([p for c in loc.values() for p in c], "location"),
               (trucks, "truck"), (planes, "airplane"), (pkgs, "package")]
    name = f"logistics-c{cities}-l{places}-a{airplanes}-p{packages}-s{seed}"
    return problem_text("logistics", name, objects, init, goal,
                        comment=f"{cities} cities x {places} places, {airplanes} airplane(s), {packages} packages")


def depots(depots: int = 1, distributors: int = 2, trucks: int = 2, crates: int = 2, seed: int = 0) -> str:
    """IPC-2002 style: one hoist and one pallet per place; the goal places every crate."""
    rng = random.Random(seed)
    places = [f"depot{i}" for i in range(depots)] + [f"distributor{i}" for i in range(distributors)]
    pallets = [f"pallet{i}" for i in range(len(places))]
    hoists = [f"hoist{i}" for i in range(len(places))]
    truck = [f"truck{i}" for i in range(trucks)]
    crate = [f"crate{i}" for i in range(crates)]
    init = [fact("at", pallets[i], p) for i, p in enumerate(places)]
    init += [fact("at", hoists[i], p) for i, p in enumerate(places)]
    init += [fact("available", h) for h in hoists]
    init += [fact("at", t, rng.choice(places)) for t in truck]
    top = {p: p for p in pallets}  # top surface of each pallet's stack
    for c in crate:
        i = rng.randrange(len(pallets))
        init += [fact("at", c, places[i]), fact("on", c, top[pallets[i]])]
        top[pallets[i]] = c
    init += [fact("clear", s) for s in top.values()]
    start = [f for f in init if f.startswith("(on ")]
    while True:  # the on facts of a random arrangement, at least half of them new
        goal_top = {p: p for p in pallets}
        goal = []
        for c in rng.sample(crate, len(crate)):
            p = rng.choice(pallets)
            goal.append(fact("on", c, goal_top[p]))
            goal_top[p] = c
        if 2 * sum(g not in start for g in goal) >= len(goal):
            break
    goal.sort()
    objects = [([p for p in places if p.startswith("depot")], "depot"),
               ([p for p in places if p.startswith("distributor")], "distributor"),
               (truck, "truck"), (pallets, "pallet"), (crate, "crate"), (hoists, "hoist")]
    name = f"depots-d{depots}-i{distributors}-t{trucks}-c{crates}-s{seed}"
    return problem_text("depots", name, objects, init, goal,
                        comment=f"{depots} depot(s), {distributors} distributors, {trucks} trucks, {crates} crates")


def driverlog(drivers: int = 2, trucks: int = 2, packages: int = 2, locations: int = 3, seed: int = 0) -> str:
    """IPC-2002 style: a connected road map; drivers walk over path points between locations."""
    rng = random.Random(seed)
    locs = [f"s{i}" for i in range(locations)]
    roads = connected_graph(locations, 0.3, rng)
    # footpaths: a spanning tree of their own (so every driver can reach every truck), plus a few more
    walks = connected_graph(locations, 0.15, rng)
    points = [f"p{i}-{j}" for i, j in walks]
    init = [fact("link", locs[i], locs[j]) for i, j in roads] + [fact("link", locs[j], locs[i]) for i, j in roads]
    for (i, j), p in zip(walks, points, strict=True):
        init += [fact("path", locs[i], p), fact("path", p, locs[i]), fact("path", locs[j], p), fact("path", p, locs[j])]
    drv = [f"driver{i}" for i in range(1, drivers + 1)]
    trk = [f"truck{i}" for i in range(1, trucks + 1)]
    pkg = [f"package{i}" for i in range(1, packages + 1)]
    goal = []
    for d in drv:
        init.append(fact("at", d, rng.choice(locs)))
        goal.append(fact("at", d, rng.choice(locs)))
    for t in trk:
        init += [fact("at", t, rng.choice(locs)), fact("empty", t)]
        if rng.random() < 0.5:
            goal.append(fact("at", t, rng.choice(locs)))
    for k in pkg:
        start = rng.choice(locs)
        init.append(fact("at", k, start))
        goal.append(fact("at", k, _other(rng, locs, start)))
    objects = [(drv, "driver"), (trk, "truck"), (pkg, "obj"), (locs + points, "location")]
    name = f"driverlog-d{drivers}-t{trucks}-p{packages}-l{locations}-s{seed}"
    return problem_text("driverlog", name, objects, init, goal,
                        comment=f"{drivers} drivers, {trucks} trucks, {packages} packages, {locations} locations")


def gripper(balls: int = 4, seed: int = 0) -> str:
    """IPC-1998: every ball from rooma to roomb (``seed`` is unused: the domain has no random part)."""
    ball = [f"ball{i}" for i in range(1, balls + 1)]
    init = ["(room rooma)", "(room roomb)", "(gripper left)", "(gripper right)", "(at-robby rooma)",
            "(free left)", "(free right)"]
    init += [fact("ball", b) for b in ball] + [fact("at", b, "rooma") for b in ball]
    goal = [fact("at", b, "roomb") for b in ball]
    return problem_text("gripper-strips", f"gripper-{balls}", [(["rooma", "roomb", "left", "right", *ball], None)],
                        init, goal, comment=f"{balls} balls from rooma to roomb")


def miconic(passengers: int = 2, floors: int = 4, seed: int = 0) -> str:
    """IPC-2000 style: each passenger from a random floor to another; the lift starts at f0."""
    rng = random.Random(seed)
    fl = [f"f{i}" for i in range(floors)]
    ps = [f"p{i}" for i in range(passengers)]
    init = [fact("above", fl[i], fl[j]) for i in range(floors) for j in range(i + 1, floors)]
    init.append(fact("lift-at", fl[0]))
    for p in ps:
        o = rng.choice(fl)
        init += [fact("origin", p, o), fact("destin", p, _other(rng, fl, o))]
    goal = [fact("served", p) for p in ps]
    return problem_text("miconic", f"miconic-p{passengers}-f{floors}-s{seed}", [(ps, "passenger"), (fl, "floor")],
                        init, goal, comment=f"{passengers} passengers, {floors} floors")


def zenotravel(aircraft: int = 1, persons: int = 2, cities: int = 3, seed: int = 0) -> str:
    """IPC-2002 style: fuel levels fl0..fl6; people and some aircraft have goal cities."""
    rng = random.Random(seed)
    city = [f"city{i}" for i in range(cities)]
    planes = [f"plane{i}" for i in range(1, aircraft + 1)]
    people = [f"person{i}" for i in range(1, persons + 1)]
    levels = [f"fl{i}" for i in range(7)]
    init = [fact("next", levels[i], levels[i + 1]) for i in range(6)]
    goal = []
    for a in planes:
        init += [fact("at", a, rng.choice(city)), fact("fuel-level", a, rng.choice(levels[1:]))]
        if rng.random() < 0.5:
            goal.append(fact("at", a, rng.choice(city)))
    for p in people:
        start = rng.choice(city)
        init.append(fact("at", p, start))
        goal.append(fact("at", p, _other(rng, city, start)))
    objects = [(planes, "aircraft"), (people, "person"), (city, "city"), (levels, "flevel")]
    return problem_text("zeno-travel", f"zenotravel-a{aircraft}-p{persons}-c{cities}-s{seed}", objects, init, goal,
                        comment=f"{aircraft} aircraft, {persons} persons, {cities} cities")


def _greedy_fuel(n: int, dist: list[list[int]], start: int, jobs: list[tuple[int, int]], rng: random.Random) -> int:
    """Fuel of a greedy delivery tour: go to the nearest pending pick-up or drop (ties at random)."""
    pos, fuel = start, 0
    waiting = list(jobs)
    carried: list[int] = []
    while waiting or carried:
        stops = [o for o, _ in waiting] + carried
        best = min(dist[pos][s] for s in stops)
        pos_next = rng.choice([s for s in stops if dist[pos][s] == best])
        fuel += best
        pos = pos_next
        carried = [d for d in carried if d != pos]
        carried += [d for o, d in waiting if o == pos and d != pos]
        waiting = [(o, d) for o, d in waiting if o != pos]
    return fuel


def nomystery(locations: int = 5, packages: int = 4, seed: int = 0) -> str:
    """IPC-2011 style: road costs 1..3; the truck's fuel is the best of 20 greedy delivery tours.

    A greedy tour always exists, so the instance is solvable; the fuel is
    tight enough that wasteful routes run dry.
    """
    rng = random.Random(seed)
    edges = connected_graph(locations, 0.25, rng)
    cost = {e: rng.randint(1, 3) for e in edges}
    dist = distances(locations, edges, cost)
    start = rng.randrange(locations)
    jobs = []
    for _ in range(packages):
        o = rng.randrange(locations)
        jobs.append((o, rng.choice([d for d in range(locations) if d != o])))
    fuel = min(_greedy_fuel(locations, dist, start, jobs, random.Random(seed * 1000 + k)) for k in range(20))
    locs = [f"l{i}" for i in range(locations)]
    levels = [f"level{i}" for i in range(fuel + 1)]
    pkg = [f"p{i}" for i in range(packages)]
    init = []
    for (i, j), c in cost.items():
        init += [fact("connected", locs[i], locs[j]), fact("connected", locs[j], locs[i]),
                 fact("fuelcost", levels[c], locs[i], locs[j]), fact("fuelcost", levels[c], locs[j], locs[i])]
    deltas = sorted({c for c in cost.values()})
    init += [fact("sum", levels[a], levels[d], levels[a + d]) for d in deltas for a in range(fuel + 1 - d)]
    init += [fact("at", "t0", locs[start]), fact("fuel", "t0", levels[fuel])]
    init += [fact("at", pkg[k], locs[o]) for k, (o, _) in enumerate(jobs)]
    goal = [fact("at", pkg[k], locs[d]) for k, (_, d) in enumerate(jobs)]
    objects = [(locs, "location"), (levels, "fuellevel"), (["t0"], "truck"), (pkg, "package")]
    return problem_text("transport-strips", f"nomystery-l{locations}-p{packages}-s{seed}", objects, init, goal,
                        comment=f"{locations} locations, {packages} packages, fuel {fuel}")
