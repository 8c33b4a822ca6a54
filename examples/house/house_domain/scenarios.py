"""Seeded house problems: fetch the cup from behind the locked study door."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, SymbolicBelief, atom

from house_domain.model import DOMAIN
from house_domain.world import HouseWorld

ROOMS = ("hall", "kitchen", "bath", "study", "bedroom")
DOORS = {  # door: (room, room, initially open, initially unlocked)
    "d_kitchen": ("hall", "kitchen", True, True),
    "d_bath": ("hall", "bath", False, True),
    "d_study": ("hall", "study", False, False),  # locked: its key is somewhere in front
    "d_bedroom": ("study", "bedroom", False, True),
}


def problem(seed: int) -> Problem:
    """The robot, the key and the cup placed at random: the key in front, the cup behind the locked door."""
    rng = random.Random(seed)
    facts = [atom("robot_in", rng.choice(["hall", "kitchen", "bath"])), atom("hand_empty"),
             atom("at", "key", rng.choice(["kitchen", "bath"])), atom("unlocks", "key", "d_study"),
             atom("at", "cup", rng.choice(["study", "bedroom"]))]
    for door, (a, b, is_open, unlocked) in DOORS.items():
        facts += [atom("connects", door, a, b), atom("connects", door, b, a)]
        facts += [atom("open", door)] * is_open + [atom("unlocked", door)] * unlocked
    objects = {**{x: "room" for x in ROOMS}, **{x: "door" for x in DOORS}, "key": "item", "cup": "item"}
    goal = Goal.of([atom("at", "cup", "kitchen")], DOMAIN.rules)
    return Problem(DOMAIN, objects, State(facts), goal, f"house-s{seed}")


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, sticky: float = 0.0) -> Episode:
    prob = problem(seed)
    world = HouseWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                       exogenous_prob=exogenous_prob, sticky=sticky)
    desc = f"house, failure p={failure_prob:g}, draught p={exogenous_prob:g}, sticky doors p={sticky:g}"
    return Episode(prob, world, SymbolicBelief(prob.init), desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "fetch": episode,
    "sticky": partial(episode, sticky=0.3),  # doors stick: opening fails 3 times in 10
    "draughty": partial(episode, exogenous_prob=0.1),  # a draught shuts an open door now and then
}
