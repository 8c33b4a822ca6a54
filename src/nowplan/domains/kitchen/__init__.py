"""The PyBullet kitchen of seed 004: drawers, occlusion, particle beliefs, four tasks.

Registered as the ``kitchen`` domain (scenarios inspect/stow/swap/cook and
their hard versions inspect-hard/…/cook-hard,
renderer, ``nowplan demo kitchen``) and as the reproduction of seed 004
(``nowplan reproduce 004``).  Needs the ``kitchen`` extra (pybullet); the
package imports without it and says so when used.
"""

from __future__ import annotations

from typing import Any

from nowplan.domains.registry import DomainSpec, register
from nowplan.experiments.reproductions import Reproduction


def _scenario(task: str) -> Any:
    def make(seed: int) -> Any:
        from nowplan.domains.kitchen.tasks import make as mk

        return mk(task, seed % 25, seed // 25)

    return make


def _hard(task: str) -> Any:
    def make(seed: int) -> Any:
        from nowplan.domains.kitchen.hard import make as mk

        return mk(task, seed % 25, seed // 25)

    return make


def _render(world: Any, belief: Any) -> bytes:
    from nowplan.domains.kitchen.render import render_png

    return render_png(world, belief)


def _demo(args: Any) -> int:
    from nowplan.domains.kitchen.demo import main

    return main(args)


def _reproduce(options: Any) -> Any:
    from nowplan.domains.kitchen.repro import run

    return run(options)


SPEC = register(
    DomainSpec(
        name="kitchen",
        description="PyBullet kitchen with drawers and occlusion, particle beliefs (seed 004)",
        scenarios={**{t: _scenario(t) for t in ("inspect", "stow", "swap", "cook")},
                   **{f"{t}-hard": _hard(t) for t in ("inspect", "stow", "swap", "cook")}},
        renderer=_render,
        default_scenario="inspect",
        demo=_demo,
        matrix_scenario="inspect",
        matrix_slow=True,
        reproductions=(Reproduction("004", "seed 004 Table I: SS-Replan variants on the kitchen tasks", _reproduce),),
    )
)
