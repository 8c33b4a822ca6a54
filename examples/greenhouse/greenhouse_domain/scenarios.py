"""Seeded greenhouse problems: water every plant and make sure none has pests."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioError, ScenarioFn, State, atom

from greenhouse_domain.model import DOMAIN, SHED, TANK, TAPS
from greenhouse_domain.world import GreenhouseBelief, GreenhouseWorld

SIZES = {  # plants, tank levels (cans it holds when full), sprayer charges
    "small": (2, 1, 2),
    "medium": (3, 2, 2),
}
PEST_PRIOR = 0.3  # the chance a plant has pests at the start
PARTICLES = 64


def problem(seed: int, size: str = "small") -> tuple[Problem, State]:
    """The problem (its initial belief is the robots' view) and the true initial state."""
    if size not in SIZES:
        raise ScenarioError(f"greenhouse: unknown size {size!r}; use one of {', '.join(SIZES)}")
    n, levels, charges = SIZES[size]
    rng = random.Random(seed)
    plants = [f"p{i}" for i in range(1, n + 1)]
    spots = {x: f"{1.0 + 2.0 * i:.1f},{3.0 + rng.choice((0.0, 1.0)):.1f}" for i, x in enumerate(plants)}
    facts = [atom("robot", "r1"), atom("robot", "r2"), atom("pose", "r1", value="0.0,0.0"),
             atom("pose", "r2", value="1.0,0.0"), atom("dry", "r1"), atom("dry", "r2"),
             atom("lies", "sprayer", SHED), atom("level", f"l{levels}"), atom("full_level", f"l{levels}"),
             atom("charge", f"c{charges}"), atom("pump_ok")]
    facts += [atom("dec", f"l{i}", f"l{i - 1}") for i in range(1, levels + 1)]
    facts += [atom("dec", f"c{i}", f"c{i - 1}") for i in range(1, charges + 1)]
    facts += [atom("spot", x, s) for x, s in spots.items()] + [atom("tap", x) for x in TAPS]
    pests = [rng.random() < PEST_PRIOR for _ in plants]
    truth = State(facts + [atom("clean", x) for x, bad in zip(plants, pests) if not bad])
    objects = {"r1": "robot", "r2": "robot", "sprayer": "tool", **{x: "plant" for x in plants},
               **{f"l{i}": "level" for i in range(levels + 1)}, **{f"c{i}": "charge" for i in range(charges + 1)}}
    goal = Goal.of([atom("watered", x) for x in plants] + [atom("clean", x) for x in plants], DOMAIN.rules)
    return Problem(DOMAIN, objects, State(facts), goal, f"greenhouse-{size}-s{seed}"), truth


def belief(facts: State, plants: list[str], seed: int, noise: float, spread: float) -> GreenhouseBelief:
    rng = random.Random(seed * 7919 + 1)
    particles = [facts.apply([atom("clean", x) for x in plants if rng.random() >= PEST_PRIOR])
                 for _ in range(PARTICLES)]
    return GreenhouseBelief(particles, seed=seed, noise=noise, spread=spread)


def episode(seed: int, size: str = "small", failure_prob: float = 0.0, exogenous_prob: float = 0.0,
            noise: float = 0.0) -> Episode:
    prob, truth = problem(seed, size)
    plants = [str(x) for (x, _) in truth.facts("spot")]
    spread = exogenous_prob / 2 / len(plants)
    bel = belief(prob.init, plants, seed, noise, spread)
    prob = Problem(prob.domain, prob.objects, bel, prob.goal, prob.name)
    world = GreenhouseWorld(DOMAIN, truth, seed=seed + 1, failure_prob=failure_prob,
                            exogenous_prob=exogenous_prob, noise=noise)
    desc = (f"greenhouse {size}, failure p={failure_prob:g}, leak/pests p={exogenous_prob:g}, "
            f"sensor noise {noise:g}")
    return Episode(prob, world, bel, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "tend": episode,
    "noisy": partial(episode, noise=0.15),
    "medium": partial(episode, size="medium"),
    "leaky": partial(episode, size="medium", exogenous_prob=0.1),
}
__all__ = ["SCENARIOS", "TANK", "episode", "problem"]
