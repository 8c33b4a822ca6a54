"""Seeded ward problems: bring the medication to the ward, get the trolley out of the corridor and
leave the isolation room's door shut."""

from __future__ import annotations

import itertools
import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, atom

from ward_domain.model import DOMAIN
from ward_domain.world import WardBelief, WardWorld, doors_of

ROOMS = ("lobby", "corridor", "pharmacy", "ward", "iso", "store")
DOORS = {"d_lobby": ("lobby", "corridor"), "d_pharm": ("corridor", "pharmacy"), "d_ward": ("corridor", "ward"),
         "d_iso": ("corridor", "iso"), "d_store": ("corridor", "store")}


def problem(seed: int) -> tuple[Problem, list[State]]:
    """The problem (its init is the true state) and the prior particles (every unseen door either way)."""
    rng = random.Random(seed)
    start = rng.choice(["lobby", "store", "ward"])
    fixed = [atom("robot_in", start), atom("hand_empty"), atom("portable", "med"), atom("bulky", "trolley"),
             atom("at", "med", "pharmacy"), atom("at", "trolley", "corridor")]
    for door, (a, b) in DOORS.items():
        fixed += [atom("connects", door, a, b), atom("connects", door, b, a)]
    is_open = {d: rng.random() < 0.5 for d in DOORS}
    init = State(fixed + [atom("open", d) for d in DOORS if is_open[d]])
    seen = {str(x) for x in doors_of(init, start)}
    unseen = sorted(d for d in DOORS if d not in seen)
    known = [atom("open", d) for d in sorted(seen) if is_open[d]]
    particles = [State(fixed + known + [atom("open", d) for d, o in zip(unseen, combo) if o])
                 for combo in itertools.product((False, True), repeat=len(unseen))] * 4
    objects = {**{r: "room" for r in ROOMS}, **{d: "door" for d in DOORS}, "med": "item", "trolley": "item"}
    goal = Goal.of([atom("at", "med", "ward"), atom("at", "trolley", "corridor", value=False),
                    atom("open", "d_iso", value=False)], DOMAIN.rules)
    return Problem(DOMAIN, objects, init, goal, f"ward-s{seed}"), particles


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, noise: float = 0.0,
            miss: float = 0.0) -> Episode:
    prob, particles = problem(seed)
    world = WardWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                      exogenous_prob=exogenous_prob, noise=noise, miss=miss)
    belief = WardBelief(particles, seed=seed + 2, noise=max(noise, 0.02), flip=max(exogenous_prob, 0.02))
    desc = (f"ward, failure p={failure_prob:g}, staff p={exogenous_prob:g}, door misread p={noise:g}, "
            f"door missed p={miss:g}")
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "round": episode,
    "busy": partial(episode, exogenous_prob=0.2, noise=0.1, miss=0.1),
}
