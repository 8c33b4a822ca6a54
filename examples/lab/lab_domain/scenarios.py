"""Seeded lab problems: scan the sample and bring it to the bench behind the lab door on floor 2."""

from __future__ import annotations

import random
from functools import partial

from nowplan.api import Episode, Goal, Problem, ScenarioFn, State, atom

from lab_domain.model import DOMAIN
from lab_domain.world import LabBelief, LabWorld, hidden_samples

FLOORS = {"f0": ("dock0", "rack0"), "f1": ("store1a", "store1b", "store1c"), "f2": ("corridor2",)}
LAB = ("d_lab", "corridor2", "lab2")  # the door between the corridor and the lab
INSIDE = ("lab2", "bench2")  # spots behind the door, joined by a hallway


def problem(seed: int, samples: int = 1) -> Problem:
    rng = random.Random(seed)
    facts = [atom("hand_empty"), atom("is_tool", "scanner"), atom("car_at", rng.choice(sorted(FLOORS)))]
    spots: dict[str, str] = {}
    for fl, names in FLOORS.items():
        lift = f"lift{fl[1]}"
        spots[lift] = fl
        facts.append(atom("lift", lift, fl))
        for n in names:
            spots[n] = fl
            facts += [atom("hallway", lift, n), atom("hallway", n, lift)]
        for a, b in zip(names, names[1:]):
            facts += [atom("hallway", a, b), atom("hallway", b, a)]
    for n in INSIDE:
        spots[n] = "f2"
    facts += [atom("hallway", INSIDE[0], INSIDE[1]), atom("hallway", INSIDE[1], INSIDE[0])]
    d, a, b = LAB
    facts += [atom("through", d, a, b), atom("through", d, b, a)]
    facts += [atom("on_floor", s, fl) for s, fl in spots.items()]
    facts += [atom("robot_at", rng.choice(["dock0", "lift0", "rack0"])),
              atom("at", "scanner", rng.choice(["rack0", "corridor2", "store1c"]))]
    wanted = [f"sample{i}" for i in range(samples)]
    for n in wanted:
        facts.append(atom("at", n, rng.choice(FLOORS["f1"])))
    objects = {**{s: "spot" for s in spots}, "f0": "floor", "f1": "floor", "f2": "floor", "d_lab": "door",
               "scanner": "thing", **{n: "thing" for n in wanted}}
    goal = Goal.of([g for n in wanted for g in (atom("scanned", n), atom("at", n, "bench2"))], DOMAIN.rules)
    return Problem(DOMAIN, objects, State(facts), goal, f"lab-s{seed}")


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, sticky: float = 0.0,
            samples: int = 1) -> Episode:
    prob = problem(seed, samples)
    world = LabWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob,
                     exogenous_prob=exogenous_prob, sticky=sticky)
    seen = State([x for x in prob.init.atoms() if x not in hidden_samples(prob.init)])
    # the robot starts on floor 0 and knows where the samples were left (they may drift before it arrives)
    belief = LabBelief(State(list(seen.atoms()) + sorted(hidden_samples(prob.init), key=str)))
    desc = f"lab, {samples} sample(s), failure p={failure_prob:g}, disturbance p={exogenous_prob:g}, sticky p={sticky:g}"
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "deliver": episode,
    "sticky": partial(episode, sticky=0.3),
    "drift": partial(episode, exogenous_prob=0.2),
    "two": partial(episode, samples=2, sticky=0.2),
}
