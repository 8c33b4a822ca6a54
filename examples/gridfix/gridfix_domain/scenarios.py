"""Seeded feeder problems: after a storm one or two of four segments are broken (which, the crew
does not know); energise both customer junctions and park the van at the depot."""

from __future__ import annotations

import itertools
import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, atom

from gridfix_domain.model import DOMAIN
from gridfix_domain.world import GridBelief, GridWorld

SITES = ("depot", "sub", "j1", "j2", "j3", "j4")
ROADS = (("depot", "sub"), ("sub", "j1"), ("j1", "j2"), ("j2", "j3"), ("j2", "j4"), ("j3", "j4"), ("j4", "depot"))
DOCKS = ("depot", "sub")
FEEDS = {"c1": ("sub", "j1"), "c2": ("j1", "j2"), "c3": ("j2", "j3"), "c4": ("j2", "j4")}
LEVELS = ("e0", "e1", "e2", "e3", "e4")
STOCK = ("s0", "s1", "s2")  # the van carries at most two spares
CUSTOMERS = ("j3", "j4")
PER_HYPOTHESIS = 6  # particles per storm hypothesis


def problem(seed: int, broken: int | None = None) -> tuple[Problem, list[State]]:
    """The problem (its init is the true state) and the prior particles: every way the storm may
    have broken one or two segments, equally likely."""
    rng = random.Random(seed)
    segs = sorted(FEEDS)
    static = [atom("dock", d) for d in DOCKS] + [atom("full", LEVELS[-1])]
    for x, y in ROADS:
        static += [atom("road", x, y), atom("road", y, x)]
    for seg, (u, w) in FEEDS.items():
        static += [atom("feeds", seg, u, w), atom("works_at", seg, w)]
    static += [atom("dec", x, y) for x, y in zip(LEVELS[1:], LEVELS)]
    static += [atom("less", x, y) for x, y in zip(STOCK[1:], STOCK)]
    common = static + [atom("van_at", "depot"), atom("batt", rng.choice(LEVELS[2:])), atom("spares", "s1"),
                       atom("live", "sub")]
    k = broken if broken is not None else rng.choice((1, 2))
    bad = set(rng.sample(segs, k))
    init = State(common + [atom("ok", x) for x in segs if x not in bad])
    hypotheses = [set(h) for m in (1, 2) for h in itertools.combinations(segs, m)]
    particles = [State(common + [atom("ok", x) for x in segs if x not in h])
                 for h in hypotheses for _ in range(PER_HYPOTHESIS)]
    objects = {**{x: "site" for x in SITES}, **{x: "segment" for x in segs}, **{x: "level" for x in LEVELS},
               **{x: "stock" for x in STOCK}}
    goal = Goal.of([atom("live", x) for x in CUSTOMERS] + [atom("van_at", "depot")], DOMAIN.rules)
    return Problem(DOMAIN, objects, init, goal, f"gridfix-s{seed}"), particles


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, miss: float = 0.0,
            fp: float = 0.0, broken: int | None = None) -> Episode:
    prob, particles = problem(seed, broken)
    world = GridWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                      exogenous_prob=exogenous_prob, miss=miss, fp=fp)
    belief = GridBelief(particles, seed=seed + 2, miss=max(miss, 0.05), fp=max(fp, 0.05),
                        trip=max(failure_prob, 0.05), gust=max(exogenous_prob / 2, 0.005))
    desc = (f"gridfix, failure p={failure_prob:g}, gust/drain p={exogenous_prob:g}, "
            f"detector misses p={miss:g}, false alarms p={fp:g}")
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "storm": episode,
    "noisy": partial(episode, miss=0.15, fp=0.1),  # the detector misses a fault 15 %, cries wolf 10 %
    "rough": partial(episode, failure_prob=0.15, exogenous_prob=0.1, miss=0.1, fp=0.05),
}
