"""Seeded warehouse problems: bring the ordered boxes, buried in stacks, to the packing slot.

Map (every road both ways; each drive takes one battery level)::

    a1 --- pack --- a2 --- a3        (a3: medium and hard)
             |
            dock                     (charging)
"""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Atom, Episode, Goal, Problem, ScenarioFn, State, atom

from warehouse_domain.belief import WarehouseBelief, arrangement_atoms
from warehouse_domain.model import DOMAIN
from warehouse_domain.world import WarehouseWorld, stacks

PACK = "pack_s"
SIZES = {  # name: (aisles, slots per aisle, boxes, ordered boxes, battery capacity, stale manifest entries)
    "small": (2, 2, 4, 1, 6, 0),
    "medium": (3, 2, 6, 1, 6, 1),
    "hard": (3, 3, 8, 2, 5, 1),
}


def layout(aisles: int, per: int) -> tuple[dict[str, list[str]], list[tuple[str, str]]]:
    names = [f"a{i + 1}" for i in range(aisles)]
    slots = {"dock": [], "pack": [PACK], **{a: [f"{a}_s{j + 1}" for j in range(per)] for a in names}}
    roads = [("dock", "pack"), ("pack", "a1"), ("pack", "a2")] + [(f"a{i}", f"a{i + 1}") for i in range(2, aisles)]
    return slots, roads


def problem(seed: int, size: str) -> tuple[Problem, dict[str, list[str]], list[str], list[str], list[Atom], State]:
    """The true problem, the slots per location, the boxes, the ordered ones, statics, and the manifest."""
    aisles, per, nbox, norder, cap, stale = SIZES[size]
    rng = random.Random(seed)
    slots_at, roads = layout(aisles, per)
    shelf = [s for k, v in slots_at.items() if k not in ("dock", "pack") for s in v]
    boxes = [f"box{i + 1}" for i in range(nbox)]
    cols: dict[str, list[str]] = {s: [] for s in [PACK] + shelf}
    for x in boxes:  # stacks of at most 3; one slot per aisle left empty when boxes allow
        choices = [s for s in shelf if len(cols[s]) < 3 and not s.endswith(f"_s{per}")] or \
                  [s for s in shelf if len(cols[s]) < 3]
        cols[rng.choice(choices)].append(x)
    buried = [x for s in shelf for x in cols[s][:-1]]
    order = rng.sample(buried if len(buried) >= norder else boxes, norder)
    levels = [f"e{i}" for i in range(cap + 1)]
    statics = [atom("road", a, c) for a, c in roads] + [atom("road", c, a) for a, c in roads]
    statics += [atom("slot_at", s, k) for k, v in slots_at.items() for s in v]
    statics += [atom("dec", levels[i + 1], levels[i]) for i in range(cap)]
    statics += [atom("low", x) for x in levels[:-1]] + [atom("full", levels[-1]), atom("dock", "dock")]
    dist = {"dock": 0}
    frontier = ["dock"]
    while frontier:  # drives from the dock (breadth first)
        here = frontier.pop(0)
        for a, c in roads + [(c, a) for a, c in roads]:
            if a == here and c not in dist:
                dist[c] = dist[here] + 1
                frontier.append(c)
    statics += [atom("enough", k, levels[i]) for k, d in dist.items() for i in range(d, cap + 1)]
    start = [atom("robot_at", rng.choice(["dock", "pack"])), atom("batt", levels[rng.randint(cap - 2, cap)]),
             atom("hand_empty")]
    init = State(start + statics + arrangement_atoms(cols))
    manifest_cols = {s: list(c) for s, c in cols.items()}
    for _ in range(stale):  # the manifest is out of date: a top box was moved to another slot
        src = rng.choice([s for s in shelf if manifest_cols[s]])
        dst = rng.choice([s for s in shelf if s != src and len(manifest_cols[s]) < 3])
        manifest_cols[dst].append(manifest_cols[src].pop())
    manifest = State(start + statics + arrangement_atoms(manifest_cols))
    objects = {**{k: "loc" for k in slots_at}, **{s: "slot" for s in cols}, **{x: "box" for x in boxes},
               **{x: "level" for x in levels}}
    goal = Goal.of([atom("in_slot", x, PACK) for x in order], DOMAIN.rules)
    return (Problem(DOMAIN, objects, init, goal, f"warehouse-{size}-s{seed}"), slots_at, boxes, order, statics,
            manifest)


def episode(seed: int, size: str = "small", failure_prob: float = 0.0, exogenous_prob: float = 0.0,
            miss: float = 0.0, false_pos: float = 0.0, fragile: float = 0.0) -> Episode:
    prob, slots_at, boxes, order, statics, manifest = problem(seed, size)
    world = WarehouseWorld(DOMAIN, prob.init, slots_at=slots_at, protected=[PACK], boxes=boxes,
                           fragile_boxes=order[:1], seed=seed + 1, failure_prob=failure_prob,
                           exogenous_prob=exogenous_prob, miss=miss, false_pos=false_pos, fragile=fragile)
    belief = WarehouseBelief(manifest, slots_at=slots_at, statics=statics, boxes=boxes)
    desc = (f"warehouse {size}: order {', '.join(order)}; failure p={failure_prob:g}, workers p={exogenous_prob:g}, "
            f"scan miss p={miss:g}, misread p={false_pos:g}, fragile pick p={fragile:g}")
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "small": episode,
    "medium": partial(episode, size="medium", fragile=0.3),
    "hard": partial(episode, size="hard", fragile=0.3, miss=0.1, false_pos=0.05),
    "busy": partial(episode, size="medium", exogenous_prob=0.2, miss=0.2, false_pos=0.1, fragile=0.3),
}
