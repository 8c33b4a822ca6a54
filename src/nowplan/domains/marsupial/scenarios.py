"""Marsupial episodes: a generated problem, a simulated world and the agent's belief.

Scenario names are ``<regime>-<packages>`` (``single-3``, ``both-10``, …, see
:data:`~nowplan.domains.marsupial.problems.REGIMES`) and ``ff`` (the seed's
FF instance).  The world is a :class:`~nowplan.worlds.symbolic.SymbolicWorld`
that can also hand a rendered picture to a *frame sink* after every vehicle
operator, which the demo turns into trace ``frame`` events.
"""

from __future__ import annotations

import base64
from collections.abc import Callable
from functools import partial
from typing import Any

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.domain import Problem
from nowplan.core.operators import Action
from nowplan.domains.marsupial.problems import REGIMES, MapSpec, ff_instance, generate
from nowplan.domains.registry import Episode, ScenarioFn
from nowplan.worlds.base import Observation
from nowplan.worlds.symbolic import SymbolicWorld

FrameSink = Callable[[bytes, str], None]
KEY_ACTIONS = ("load", "unload", "travel")
MAX_PACKAGES = 10


class MarsupialWorld(SymbolicWorld):
    """The symbolic world, with its map for rendering and an optional frame sink."""

    def __init__(self, problem: Problem, spec: MapSpec, *, seed: int = 0, failure_prob: float = 0.0) -> None:
        super().__init__(problem.domain, problem.init, seed=seed, failure_prob=failure_prob)
        self.spec = spec
        self.problem = problem
        self.frame_sink: FrameSink | None = None

    def execute(self, action: Action) -> Observation:
        obs = super().execute(action)
        if self.frame_sink is not None and action.name in KEY_ACTIONS:
            from nowplan.domains.marsupial.render import render_png

            self.frame_sink(render_png(self.spec, self.state, title=str(action)), str(action))
        return obs


def data_uri(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def make_episode(problem: Problem, spec: MapSpec, seed: int, failure_prob: float = 0.0) -> Episode:
    world = MarsupialWorld(problem, spec, seed=seed + 1, failure_prob=failure_prob)
    return Episode(problem, world, SymbolicBelief(problem.init), problem.name)


def episode(regime: str, n_packages: int, seed: int, failure_prob: float = 0.0) -> Episode:
    prob, spec = generate(regime, n_packages, seed)
    ep = make_episode(prob, spec, seed, failure_prob)
    ep.description = f"marsupial logistics, {REGIMES[regime]}, {n_packages} packages"
    return ep


def ff_episode(seed: int) -> Episode:
    prob, spec = ff_instance(seed)
    ep = make_episode(prob, spec, seed)
    ep.description = "seed 002's FF instance: 8 locations, 2 airports, one single-cell package"
    return ep


def scenarios() -> dict[str, ScenarioFn]:
    out: dict[str, ScenarioFn] = {}
    for regime in REGIMES:
        for n in range(1, MAX_PACKAGES + 1):
            out[f"{regime}-{n}"] = partial(episode, regime, n)
            out[f"{regime}-{n}-failures"] = partial(episode, regime, n, failure_prob=0.1)
    out["ff"] = ff_episode
    return out


def renderer(world: Any, belief: Any) -> bytes:
    """The registry's renderer: the world's true state (map and cargo bays) as PNG bytes."""
    from nowplan.domains.marsupial.render import render_png

    return render_png(world.spec, world.state)
