"""Seeded mine problems: find the gem in one of three galleries, store it at the shaft, leave the
gate shut."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, atom

from mine_domain.model import DOMAIN
from mine_domain.world import MineBelief, MineWorld

PLACES = ("shaft", "hall", "east", "west", "deep")
GALLERIES = ("east", "west", "deep")  # where the gem may lie
LEVELS = ("e0", "e1", "e2", "e3", "e4")
PER_PLACE = 20  # particles per gallery


def problem(seed: int) -> tuple[Problem, list[State]]:
    """The problem (its init is the true state) and the prior particles (the gem in each gallery)."""
    rng = random.Random(seed)
    static = [atom("base", "shaft"), atom("full", LEVELS[-1]), atom("chute", "hall", "deep"),
              atom("gated", "gate", "shaft", "hall"), atom("gated", "gate", "hall", "shaft")]
    for a, b in (("hall", "east"), ("hall", "west")):
        static += [atom("tunnel", a, b), atom("tunnel", b, a)]
    static += [atom("dec", a, b) for a, b in zip(LEVELS[1:], LEVELS)]
    static += [atom("dec2", a, b) for a, b in zip(LEVELS[2:], LEVELS)]
    common = static + [atom("robot_at", "shaft"), atom("hand_empty"), atom("batt", rng.choice(LEVELS[1:4]))]
    gem = rng.choice(GALLERIES)
    init = State(common + [atom("at", "gem", gem)])
    particles = [State(common + [atom("at", "gem", g)]) for g in GALLERIES for _ in range(PER_PLACE)]
    objects = {**{p: "place" for p in PLACES}, **{x: "level" for x in LEVELS}, "gem": "item", "gate": "gate"}
    goal = Goal.of([atom("stored", "gem"), atom("open", "gate", value=False)], DOMAIN.rules)
    return Problem(DOMAIN, objects, init, goal, f"mine-s{seed}"), particles


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, miss: float = 0.0,
            fp: float = 0.0) -> Episode:
    prob, particles = problem(seed)
    world = MineWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                      exogenous_prob=exogenous_prob, miss=miss, fp=fp)
    belief = MineBelief(particles, GALLERIES, seed=seed + 2, miss=max(miss, 0.05), fp=max(fp, 0.05))
    desc = (f"mine, failure p={failure_prob:g}, drain/draught p={exogenous_prob:g}, "
            f"detector misses p={miss:g}, false beeps p={fp:g}")
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "dig": episode,
    "noisy": partial(episode, miss=0.1, fp=0.1),  # the detector misses and lies one time in ten
    "rough": partial(episode, failure_prob=0.1, exogenous_prob=0.1, miss=0.1, fp=0.1),
}
