"""The engine's hierarchical logistics domain (registered as ``logistics``)."""

from __future__ import annotations

from functools import partial

from nowplan.domains.logistics.model import DOMAIN
from nowplan.domains.logistics.render import render_png
from nowplan.domains.logistics.scenarios import SIZES, episode, generate
from nowplan.domains.registry import DomainSpec, register

_scenarios = {}
for _name in SIZES:
    _scenarios[_name] = partial(episode, _name)
    _scenarios[f"{_name}-failures"] = partial(episode, _name, failure_prob=0.2)
    _scenarios[f"{_name}-exogenous"] = partial(episode, _name, exogenous_prob=0.1)

SPEC = register(
    DomainSpec(
        name="logistics",
        description="packages moved by trucks within cities and airplanes between airports",
        scenarios=_scenarios,
        default_scenario="small",
        matrix_scenario="tiny-failures",
        renderer=render_png,
        model=DOMAIN,
    )
)

__all__ = ["DOMAIN", "SPEC", "SIZES", "episode", "generate"]
