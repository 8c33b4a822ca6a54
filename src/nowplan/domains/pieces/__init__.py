"""Shuffled pieces seen by a camera (seed 003), registered as the ``pieces`` domain.

Registers the domain's scenarios, renderer and demo, its monitor support
(model distance, the seed's means-ends planner, arm re-routing) and the
reproduction of seed 003.
"""

from __future__ import annotations

from functools import partial
from typing import Any

from nowplan.domains.pieces.model import DOMAIN
from nowplan.domains.pieces.scenarios import SIZES, episode, generate, make_episode
from nowplan.domains.registry import DomainSpec, register
from nowplan.experiments.reproductions import Reproduction

DISTURBED = 0.2

_scenarios = {}
for _name in SIZES:
    _scenarios[_name] = partial(episode, _name)
    _scenarios[f"{_name}-disturbed"] = partial(episode, _name, disturbance_prob=DISTURBED)


def _render(world: Any, belief: Any) -> bytes:
    from nowplan.domains.pieces.demo import render_png

    return render_png(world, belief)


def _demo(args: Any) -> int:
    from nowplan.domains.pieces.demo import main

    return main(args)


def _reproduce(options: Any) -> Any:
    from nowplan.domains.pieces.reproduction import reproduce_003

    return reproduce_003(options)


SPEC = register(
    DomainSpec(
        name="pieces",
        description="shuffled chess pieces on a board, seen by a camera, moved by an arm (seed 003)",
        scenarios=_scenarios,
        renderer=_render,
        default_scenario="medium",
        demo=_demo,
        matrix_scenario="tiny-disturbed",
        matrix_slow=True,
        model=DOMAIN,
        reproductions=(Reproduction(
            "003", "seed 003: expected-vs-observed replanning on shuffled pieces under disturbances", _reproduce,
        ),),
    )
)

__all__ = ["DOMAIN", "SPEC", "SIZES", "episode", "generate", "make_episode"]
