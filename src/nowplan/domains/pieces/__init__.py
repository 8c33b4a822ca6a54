"""Shuffled pieces seen by a camera (seed 003), registered as the ``pieces`` domain.

Registers the domain's scenarios, renderer and demo, its monitor support
(model distance, the seed's means-ends planner, arm re-routing) and the
reproduction of seed 003.
"""

from __future__ import annotations

from functools import partial

from nowplan.acting.monitor_support import register_support
from nowplan.domains.pieces.model import DOMAIN
from nowplan.domains.pieces.scenarios import SIZES, episode, generate, make_episode
from nowplan.domains.pieces.support import SUPPORT
from nowplan.domains.registry import DomainSpec, register

DISTURBED = 0.2

_scenarios = {}
for _name in SIZES:
    _scenarios[_name] = partial(episode, _name)
    _scenarios[f"{_name}-disturbed"] = partial(episode, _name, disturbance_prob=DISTURBED)


SPEC = register(
    DomainSpec(
        name="pieces",
        description="shuffled chess pieces on a board, seen by a camera, moved by an arm (seed 003)",
        scenarios=_scenarios,
        default_scenario="medium",
    )
)
register_support(DOMAIN.name, SUPPORT)

__all__ = ["DOMAIN", "SPEC", "SIZES", "episode", "generate", "make_episode"]
