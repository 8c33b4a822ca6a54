"""Marsupial logistics (seed 002): trucks and a plane whose cargo bays are grids with a loader robot.

Registers the ``marsupial`` domain (scenarios ``<regime>-<packages>`` and
``ff``, a renderer and a demo) and the reproduction of seed 002.
"""

from __future__ import annotations

import argparse
import importlib.util
from typing import Any

from nowplan.domains.marsupial.model import PLANNER, make_domain
from nowplan.domains.marsupial.problems import REGIMES, ff_instance, generate
from nowplan.domains.marsupial.scenarios import data_uri, episode, renderer, scenarios
from nowplan.domains.registry import DomainSpec, register
from nowplan.experiments.reproductions import Reproduction

DEMO_PACKAGES = {"tiny": 2, "small": 3, "medium": 4, "large": 6}


def _reproduce(options: Any) -> Any:
    from nowplan.domains.marsupial.repro import reproduce

    return reproduce(options)


def demo(args: argparse.Namespace) -> int:
    """``nowplan demo marsupial``: RCHPN on a single-origin problem, with rendered frames."""
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.trace import Trace
    from nowplan.tree import render_text

    n = DEMO_PACKAGES.get(getattr(args, "size", "medium"), 4)
    ep = episode("single", n, args.seed, failure_prob=getattr(args, "failure_prob", 0.0) or 0.0)
    print(f"nowplan demo marsupial: {ep.description}, seed {args.seed}, strategy hpn+peephole")
    print(f"goal: {ep.problem.goal}\n")
    args.out.mkdir(parents=True, exist_ok=True)
    path = args.out / "trace.jsonl"
    with Trace(path) as trace:
        ep.world.frame_sink = lambda png, caption: trace.emit(
            "frame", n=len(trace.of("action")), image=data_uri(png), caption=caption
        )
        trace.emit("frame", n=0, image=data_uri(renderer(ep.world, ep.belief)), caption="start")
        metrics = run_episode(ep, parse_strategy("hpn+peephole", planner=PLANNER), seed=args.seed, trace=trace)
    print(render_text(trace.events, max_lines=80))
    print()
    print(metrics.summary())
    print(f"\ntrace: {path}")
    from nowplan.viz.animation import frames_of, write_captioned_gif

    pngs, captions = frames_of(trace.events)
    if pngs:
        header = ("Marsupial logistics (seed 002's RCHPN). Map: pink circles airports, lines roads (dashed: "
                  "flights), blue squares trucks, triangle the plane, small discs packages on the ground. "
                  "Right: each cargo bay's grid, beige storage, grey load region, packages in colour, "
                  "the loader robot in red.")
        gif = write_captioned_gif(pngs, args.out / "marsupial.gif", header, captions)
        print(f"animation: {gif} ({len(pngs)} frames)")
    if importlib.util.find_spec("nowplan.viz.viewer") is not None:
        from nowplan.viz.viewer import write_viewer

        page = args.out / "trace.html"
        write_viewer(path, page)
        print(f"viewer: {page} (open it in a browser)")
    return 0 if metrics.outcome.value == "reached" else 1


SPEC = register(
    DomainSpec(
        name="marsupial",
        description="marsupial logistics: trucks and a plane with grid cargo bays and loader robots (seed 002)",
        scenarios=scenarios(),
        renderer=renderer,
        default_scenario="single-3",
        demo=demo,
        extras={"regimes": dict(REGIMES)},
        matrix_scenario="single-2",
        reproductions=(Reproduction("002", "RCHPN vs HPN on marsupial logistics (Figs. 3 and 4)", _reproduce),),
        planner=PLANNER,
    )
)

__all__ = ["SPEC", "REGIMES", "episode", "ff_instance", "generate", "make_domain"]
