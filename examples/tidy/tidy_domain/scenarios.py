"""Seeded tidying problems: books, toys and cups to put away, stacked so that some must go first,
one of them behind a locked door whose key lies under a cup."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, atom

from tidy_domain.belief import TidyBelief, house_state
from tidy_domain.model import DOMAIN, DOMAIN_SPOTS
from tidy_domain.world import TidyWorld

ROOMS = ("hall", "kitchen", "living", "bedroom", "bath")
DOORS = {  # door: (room, room, initially open, initially unlocked)
    "d_kitchen": ("hall", "kitchen", True, True),
    "d_living": ("hall", "living", False, True),
    "d_arch": ("kitchen", "living", True, True),
    "d_bed": ("hall", "bedroom", False, False),  # locked: its key lies under the cup
    "d_bath": ("bedroom", "bath", False, True),
}
SURFACES = {"table": "living", "bin": "living", "counter": "kitchen", "rack": "kitchen", "shelf": "bedroom",
            "hamper": "bath"}
SPOTS = {f"f_{rm}{i}": rm for rm in ROOMS for i in (1, 2)}
THINGS = ("book", "box", "toy", "cup", "key", "sock")
GOALS = {"tidy": (("book", "shelf"), ("toy", "bin"), ("cup", "rack")),
         "full": (("book", "shelf"), ("toy", "bin"), ("cup", "rack"), ("sock", "hamper"))}


def neighbours() -> dict[str, list[str]]:
    out: dict[str, list[str]] = {rm: [] for rm in ROOMS}
    for a, b, _, _ in DOORS.values():
        out[a].append(b)
        out[b].append(a)
    return out


def problem(seed: int, goal: str, spots: bool = False) -> tuple[Problem, TidyBelief]:
    """The problem (its init is the true state) and the robot's belief (the same map, to be made stale)."""
    rng = random.Random(seed)
    stack = ["book", "box", "toy"]
    rng.shuffle(stack)  # bottom to top on the living-room table
    things: dict[str, tuple[str, str]] = {}
    below = "table"
    for t in stack:
        things[t] = (below, "living")
        below = t
    things["key"] = ("counter", "kitchen")
    things["cup"] = ("key", "kitchen")
    sock_spot = rng.choice(["f_hall1", "f_living1", "f_bedroom1"])
    things["sock"] = (sock_spot, SPOTS[sock_spot])
    statics = [atom("opens", "key", "d_bed")]
    for dr, (a, b, _, _) in DOORS.items():
        statics += [atom("connects", dr, a, b), atom("connects", dr, b, a)]
    statics += [atom("in", s, rm) for s, rm in {**SURFACES, **SPOTS}.items()]
    doors = {dr: (o, u) for dr, (_, _, o, u) in DOORS.items()}
    robot = rng.choice(["hall", "kitchen", "living"])
    supports = [*SURFACES, *SPOTS, *THINGS]
    init = house_state(statics, robot, None, doors, things, supports)
    objects = {**{x: "room" for x in ROOMS}, **{x: "door" for x in DOORS}, **{x: "surface" for x in SURFACES},
               **{x: "surface" for x in SPOTS}, **{x: "thing" for x in THINGS if x != "key"}, "key": "key"}
    domain = DOMAIN_SPOTS if spots else DOMAIN
    g = Goal.of([atom("on", t, s) for t, s in GOALS[goal]], domain.rules)
    belief = TidyBelief(statics=statics, robot=robot, doors=doors, things=things, supports=supports, spots=SPOTS,
                        neighbours=neighbours())
    return Problem(domain, objects, init, g, f"tidy-{goal}-s{seed}"), belief


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, drop: float = 0.0,
            goal: str = "tidy", spots: bool = False) -> Episode:
    prob, belief = problem(seed, goal, spots)
    world = TidyWorld(prob.domain, prob.init, seed=seed + 1, failure_prob=failure_prob, exogenous_prob=exogenous_prob,
                      drop=drop)
    desc = f"tidy ({goal}{', spots from a generator' if spots else ''}), failure p={failure_prob:g}, cat p={exogenous_prob:g}, gripper drops p={drop:g}"
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "tidy": episode,
    "full": partial(episode, goal="full"),  # the sock too, to the hamper in the bath
    "clumsy": partial(episode, failure_prob=0.1, drop=0.1),  # grips fail, carried things fall
    "spots": partial(episode, spots=True),  # a thing put aside goes where the generator ``spot`` says
    "cat": partial(episode, exogenous_prob=0.1, drop=0.05),  # the cat moves things unseen
}
