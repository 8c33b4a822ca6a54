"""Seeded mill-shop problems: six orders of two kinds, eight blanks in the store, two AGVs."""

from __future__ import annotations

import random
from functools import partial
from typing import Any, Callable

from nowplan.api import Atom, Episode, Goal, Problem, ScenarioFn, State, SymbolicBelief, atom

from millshop_domain.model import DOMAIN
from millshop_domain.world import ShopWorld

STATIONS = ("store", "lathe", "booth", "dock")
LINKS = (("store", "lathe"), ("lathe", "booth"), ("booth", "dock"), ("dock", "store"))
AGVS = ("agv1", "agv2")
KINDS = ("shaft", "gear")
# what is left to do for a part in each state (a rough count of actions, with the moves)
STAGE_COST = {"raw": 16.0, "turned": 10.0, "painted": 4.0}


class ShopBelief(SymbolicBelief):
    """The controller's point belief (adopts each report) with a goal-distance estimate of its own."""

    @property
    def planning_heuristic(self) -> Callable[[Goal, Any, Callable[[Atom], bool]], float]:
        return estimate

    def copy(self) -> ShopBelief:
        return ShopBelief(self.state)


def _stage(belief: Any, part: str) -> float:
    for name in ("painted", "turned", "raw"):
        if belief.value((name, (part,))):
            return STAGE_COST[name]
    return float("inf")


def estimate(goal: Goal, belief: Any, holds: Callable[[Atom], bool]) -> float:
    """Unmet goal atoms, an order priced by the most advanced usable part of its kind."""
    wants = {str(x): str(y) for (x, y) in belief.facts("wants")}
    kinds: dict[str, list[str]] = {}
    usable = {str(x) for (x, _) in belief.facts("at")} | {str(x) for (_, x) in belief.facts("carrying")}
    for (p, kk) in belief.facts("kind"):
        if str(p) in usable:
            kinds.setdefault(str(kk), []).append(str(p))
    h = 0.0
    for g in goal.atoms:
        if holds(g):
            continue
        if g.predicate == "filled":
            h += min((_stage(belief, p) for p in kinds.get(wants.get(str(g.args[0]), ""), [])), default=50.0)
        elif g.predicate in ("painted", "turned"):
            h += 3.0
        elif g.predicate in ("at", "carrying"):
            h += 2.0
        else:
            h += 1.0
    return h


def problem(seed: int, orders: int = 6, spares: int = 1) -> Problem:
    """Orders of random kinds; per kind as many blanks as its orders plus ``spares``; AGVs at random stops."""
    rng = random.Random(seed)
    facts = [atom("lathe", "lathe"), atom("booth", "booth"), atom("dock", "dock"),
             atom("machine", "lathe"), atom("machine", "booth")]
    for x, y in LINKS:
        facts += [atom("link", x, y), atom("link", y, x)]
    for agv in AGVS:
        facts += [atom("agv_at", agv, rng.choice(STATIONS)), atom("free", agv)]
    kinds = [KINDS[i % 2] if i < 2 else rng.choice(KINDS) for i in range(orders)]
    names = [f"o{i + 1}" for i in range(orders)]
    facts += [x for n, kk in zip(names, kinds) for x in (atom("open", n), atom("wants", n, kk))]
    parts: dict[str, str] = {}
    for kk in KINDS:
        for j in range(kinds.count(kk) + spares):
            p = f"{kk}{j + 1}"
            parts[p] = kk
            facts += [atom("at", p, "store"), atom("raw", p), atom("clean", p), atom("kind", p, kk)]
    objects = {**{x: "station" for x in STATIONS}, **{x: "agv" for x in AGVS}, **{x: "kind" for x in KINDS},
               **{x: "order" for x in names}, **{x: "part" for x in parts}}
    goal_atoms = [atom("filled", n) for n in names]
    goal_atoms += [atom("agv_at", agv, "store") for agv in AGVS]  # park both AGVs
    goal_atoms += [atom("on", m, value=False) for m in ("lathe", "booth")]  # and leave the machines off
    return Problem(DOMAIN, objects, State(facts), Goal.of(goal_atoms, DOMAIN.rules), f"millshop-s{seed}")


def episode(seed: int, failure_prob: float = 0.0, exogenous_prob: float = 0.0, scrap: float = 0.0,
            smudge: float = 0.0, lag: float = 0.0, orders: int = 6, spares: int = 1,
            heuristic: bool = False) -> Episode:
    prob = problem(seed, orders, spares)
    world = ShopWorld(DOMAIN, prob.init, seed=seed + 1, failure_prob=failure_prob, exogenous_prob=exogenous_prob,
                      scrap=scrap, smudge=smudge, lag=lag)
    belief = ShopBelief(prob.init) if heuristic else SymbolicBelief(prob.init)
    desc = (f"millshop, {orders} orders, {spares} spare(s) per kind, failure p={failure_prob:g}, power trips "
            f"p={exogenous_prob:g}, scrap p={scrap:g}, smudge p={smudge:g}, late reports p={lag:g}")
    return Episode(prob, world, belief, desc)


SCENARIOS: dict[str, ScenarioFn] = {
    "shop": episode,
    "small": partial(episode, orders=3),
    "spoilage": partial(episode, scrap=0.15, smudge=0.2),  # the matrix scenario: the world's own faults
    "trips": partial(episode, exogenous_prob=0.15),  # machines trip off
    "laggy": partial(episode, lag=0.2),  # one report in five comes late
    "rough": partial(episode, failure_prob=0.1, exogenous_prob=0.1, scrap=0.1, smudge=0.1, lag=0.1),
}
