"""NAMO: navigation among (unknown, uncertain) movable obstacles, in fog (seed 000 IV).

A 2-D robot with a footprint and a range- and field-of-view-limited sensor
must reach a goal; walls are known in advance, movable obstacles are not,
unobserved space is fog.  The agent's belief is a fog grid, a Gaussian
robot pose and a Kalman filter per detected object; the world is a
separate simulator with noisy motion, grasps and looks.  Registered as the
``namo`` domain (scenarios, renderer, ``nowplan demo namo``) and as the
reproduction of seed 000 (``nowplan reproduce 000``).
"""

from __future__ import annotations

from typing import Any

from nowplan.domains.namo.model import DOMAIN, build_domain
from nowplan.domains.namo.scenarios import SCENARIOS, episode, make
from nowplan.domains.registry import DomainSpec, register
from nowplan.experiments.reproductions import Reproduction


def _render(world: Any, belief: Any) -> bytes:
    from nowplan.domains.namo.render import render_png

    return render_png(world, belief)


def _demo(args: Any) -> int:
    from nowplan.domains.namo.demo import main

    return main(args)


def _reproduce(options: Any) -> Any:
    from nowplan.domains.namo.reproduction import reproduce_000

    return reproduce_000(options)


SPEC = register(
    DomainSpec(
        name="namo",
        description="navigation among unknown movable obstacles in fog (seed 000)",
        scenarios=SCENARIOS,
        renderer=_render,
        default_scenario="domain1",
        demo=_demo,
        matrix_scenario="simple",
        reproductions=(Reproduction("000", "seed 000: BHPN reconsideration on NAMO (Table I)", _reproduce),),
    )
)

__all__ = ["DOMAIN", "SPEC", "SCENARIOS", "build_domain", "episode", "make"]
