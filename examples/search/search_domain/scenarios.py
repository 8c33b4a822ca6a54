"""Seeded tidying problems: store two (or three) items whose places the robot only guesses."""

from __future__ import annotations

import itertools
import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, atom

from search_domain.model import DOMAIN
from search_domain.world import SearchBelief, SearchWorld

PLACES = ("base", "desk", "shelf", "sofa", "bed")  # a ring: base-desk-shelf-sofa-bed-base
ITEMS = ("book", "mug", "sock")


def problem(seed: int, wanted: int = 2) -> tuple[Problem, list[State]]:
    """The problem (its init is the true state) and the prior particles: every placement of the items."""
    rng = random.Random(seed)
    ring = list(PLACES)
    static = [atom("base", "base")]
    for a, b in zip(ring, ring[1:] + ring[:1]):
        static += [atom("adjacent", a, b), atom("adjacent", b, a)]
    where = {x: rng.choice(ring[1:]) for x in ITEMS}
    common = static + [atom("robot_at", "base"), atom("hand_empty")]
    init = State(common + [atom("at", x, p) for x, p in where.items()])
    particles = [State(common + [atom("at", x, p) for x, p in zip(ITEMS, combo)])
                 for combo in itertools.product(ring[1:], repeat=len(ITEMS))]
    objects = {**{p: "place" for p in PLACES}, **{x: "item" for x in ITEMS}}
    goal = Goal.of([atom("stored", x) for x in ITEMS[:wanted]], DOMAIN.rules)
    return Problem(DOMAIN, objects, init, goal, f"search-s{seed}"), particles


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, miss: float = 0.0,
            wanted: int = 2) -> Episode:
    prob, particles = problem(seed, wanted)
    world = SearchWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                        exogenous_prob=exogenous_prob, miss=miss)
    belief = SearchBelief(particles, seed=seed + 2, miss=max(miss, 0.05))
    desc = f"search, {wanted} items, failure p={failure_prob:g}, moved p={exogenous_prob:g}, missed detections p={miss:g}"
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "tidy": episode,
    "missy": partial(episode, miss=0.2),
    "messy": partial(episode, miss=0.1, exogenous_prob=0.1),
    "three": partial(episode, miss=0.1, wanted=3),
}
