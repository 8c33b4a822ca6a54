"""Seeded drone problems: parcels at random poses on an 8 x 8 field, chargers, a depot in a corner."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, atom

from drone_domain.belief import DroneBelief, Pose
from drone_domain.model import DOMAIN
from drone_domain.world import DroneWorld


def problem(seed: int, parcels: int = 2) -> tuple[Problem, Pose, float, dict[str, Pose]]:
    rng = random.Random(seed)
    start = (round(rng.uniform(0, 8), 2), round(rng.uniform(0, 8), 2))
    battery = round(rng.uniform(0.3, 0.8), 2)
    where = {f"p{i}": (round(rng.uniform(0, 8), 2), round(rng.uniform(0, 8), 2)) for i in range(parcels)}
    goal = Goal.of([atom("Delivered", x) for x in where], DOMAIN.rules)
    return Problem(DOMAIN, {x: "parcel" for x in where}, None, goal, f"drone-s{seed}"), start, battery, where


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, fix_sigma: float = 0.05,
            miss: float = 0.0, slip: float = 0.0, parcels: int = 2) -> Episode:
    prob, start, battery, where = problem(seed, parcels)
    world = DroneWorld(start, battery, where, seed=seed + 1, failure_prob=failure_prob,
                       exogenous_prob=exogenous_prob, fix_sigma=fix_sigma, miss=miss, slip=slip)
    belief = DroneBelief(start, 0.1, battery, dict(where), fix_sigma=fix_sigma)
    desc = (f"drone, {parcels} parcels, failure p={failure_prob:g}, gust p={exogenous_prob:g}, "
            f"fix sigma={fix_sigma:g}, fix missed p={miss:g}, grasp slip p={slip:g}")
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "deliver": episode,
    "windy": partial(episode, exogenous_prob=0.2, fix_sigma=0.15, miss=0.2, slip=0.2),
    "three": partial(episode, parcels=3, slip=0.1),
}
