"""``nowplan demo``: hierarchical logistics solved end to end, with failures."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.commands.common import nonneg_int, probability
from nowplan.domains.logistics import episode
from nowplan.domains.registry import domain_names, get_domain
from nowplan.errors import ScenarioError
from nowplan.trace import Trace
from nowplan.tree import render_text
from nowplan.domains.logistics.render import render_png
from nowplan.viz.animation import frames_of, write_captioned_gif
from nowplan.viz.viewer import write_viewer


def register(sub: Any) -> None:
    p = sub.add_parser(
        "demo",
        help="solve a hierarchical logistics problem end to end and print the plan tree",
        description=(
            "Runs HPN on a seeded medium logistics problem (3 cities, 5 packages) in a simulated "
            "world where actions fail with some probability; prints the plan tree (steps marked * "
            "were executed or refined) and the metrics, and writes the trace."
        ),
    )
    p.add_argument(
        "domain", nargs="?", default="logistics",
        help="which domain's demo to run (default: logistics; any registered domain with a demo)",
    )
    p.add_argument("--scenario", help="scenario for a domain's own demo (default: the domain's choice)")
    p.add_argument("--seed", type=nonneg_int, default=0, help="problem and world seed (default 0)")
    p.add_argument("--size", default="medium", choices=["tiny", "small", "medium", "large"])
    p.add_argument("--failure-prob", type=probability, default=0.1, help="action failure probability (default 0.1)")
    p.add_argument("--out", type=Path, default=None,
                   help="folder for the trace, viewer page and animation (default out/demo/DOMAIN)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    if args.out is None:  # one folder per domain: the demos never overwrite each other's files
        args.out = Path("out/demo") / args.domain
    if args.domain != "logistics":
        spec = get_domain(args.domain)
        if spec.demo is None:
            with_demo = [n for n in domain_names() if n == "logistics" or get_domain(n).demo]
            raise ScenarioError(
                f"domain '{args.domain}' has no demo; domains with a demo: {', '.join(with_demo)}"
            )
        return spec.demo(args)
    ep = episode(args.size, args.seed, failure_prob=args.failure_prob)
    print(f"nowplan demo: {ep.description}, seed {args.seed}")
    print(f"goal: {ep.problem.goal}\n")
    args.out.mkdir(parents=True, exist_ok=True)
    trace_path = args.out / "trace.jsonl"
    with Trace(trace_path) as trace:  # a frame of the world after every action (the animation)
        metrics = run_episode(ep, parse_strategy("hpn"), seed=args.seed, trace=trace, render=render_png)
    print("plan tree (* = step executed or refined; <abs-k> = k criticality classes still hidden):")
    print(render_text(trace.events, max_lines=120))
    print()
    print(metrics.summary())
    print(f"\ntrace: {trace_path}")
    pngs, captions = frames_of(trace.events)
    if pngs:
        header = ("Logistics: cities as rings of locations (airports pink), trucks blue squares, airplanes "
                  "orange triangles (their load in brackets), packages green discs; one frame per action.")
        gif = write_captioned_gif(pngs, args.out / "logistics.gif", header, captions, ms_per_frame=500)
        print(f"animation: {gif} ({len(pngs)} frames)")
    page = args.out / "trace.html"
    write_viewer(trace_path, page)
    print(f"viewer: {page} (open it in a browser)")
    return 0 if metrics.outcome.value == "reached" else 1
