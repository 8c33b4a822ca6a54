"""Seeded ferry problems: four passengers on four docks, two boats at the fuel dock."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, SymbolicBelief, atom

from ferry_domain.model import DOMAIN
from ferry_domain.world import FerryWorld

DOCKS = ("harbor", "pier", "cove", "isle")
LANES = (("harbor", "pier"), ("cove", "isle"))
MOUTHS = ("pier", "cove")  # the channel's two ends
BOATS = ("ferry_a", "ferry_b")
LEVELS = ("f0", "f1", "f2", "f3", "f4")
COUNTS = ("s0", "s1", "s2")  # free seats: two per boat


def problem(seed: int, passengers: int = 4) -> Problem:
    """Both boats at the harbour with random fuel; passengers on random docks wanting other docks."""
    rng = random.Random(seed)
    facts = [atom("fuel_dock", "harbor"), atom("full", LEVELS[-1]), atom("empty", LEVELS[0]), atom("channel_free")]
    facts += [atom("mouth", m) for m in MOUTHS]
    for a, c in LANES:
        facts += [atom("lane", a, c), atom("lane", c, a)]
    facts += [atom("dec", x, y) for x, y in zip(LEVELS[1:], LEVELS)]
    facts += [atom("below_full", x) for x in LEVELS[:-1]]
    facts += [atom("one_less", x, y) for x, y in zip(COUNTS, COUNTS[1:])]
    for boat in BOATS:
        facts += [atom("boat_at", boat, "harbor"), atom("fuel", boat, rng.choice(LEVELS[2:])),
                  atom("seats", boat, COUNTS[-1])]
    people = [f"p{i}" for i in range(1, passengers + 1)]
    for who in people:
        src = rng.choice(DOCKS)
        facts += [atom("at", who, src), atom("wants", who, rng.choice([x for x in DOCKS if x != src]))]
    objects = {**{x: "dock" for x in DOCKS}, **{x: "boat" for x in BOATS}, **{x: "level" for x in LEVELS},
               **{x: "count" for x in COUNTS}, **{x: "passenger" for x in people}}
    goal_atoms = [atom("served", who) for who in people]
    goal_atoms += [atom("in_channel", boat, value=False) for boat in BOATS]
    goal_atoms += [atom("boat_at", boat, "harbor", value=False) for boat in BOATS]  # leave the fuel dock clear
    goal = Goal.of(goal_atoms, DOMAIN.rules)
    return Problem(DOMAIN, objects, State(facts), goal, f"ferry-s{seed}")


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, balk: float = 0.0,
            passengers: int = 4) -> Episode:
    prob = problem(seed, passengers)
    world = FerryWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                       exogenous_prob=exogenous_prob, balk=balk)
    desc = (f"ferry, {passengers} passengers, failure p={failure_prob:g}, change of mind p={exogenous_prob:g}, "
            f"balking p={balk:g}")
    return Episode(prob, world, SymbolicBelief(prob.init), desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "ferry": episode,
    "balky": partial(episode, balk=0.3),  # boarding fails 3 times in 10
    "fickle": partial(episode, exogenous_prob=0.15),  # passengers change their minds
    "rough": partial(episode, failure_prob=0.1, exogenous_prob=0.1, balk=0.2),
}
