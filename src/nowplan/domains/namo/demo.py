"""``nowplan demo namo``: a robot clears its way through fog, with pictures.

Runs one NAMO scenario under BHPN with selective replanning and foresight; writes the trace (with a PNG frame
after every action, embedded by the viewer), the frames as files and an
animated GIF, and prints the metrics.  ``--failure-prob`` is the world's
grasp-failure probability.
"""

from __future__ import annotations

import argparse
import logging
from dataclasses import replace
from pathlib import Path

from nowplan.acting.strategy import parse_strategy
from nowplan.domains.namo.render import write_gif
from nowplan.domains.namo.runner import run_recorded
from nowplan.domains.namo.scenarios import SCENARIOS, episode
from nowplan.errors import ScenarioError
from nowplan.trace import Trace

log = logging.getLogger(__name__)

DEMO_SCENARIO = "domain1"
DEMO_STRATEGY = "hpn+foresight+selective"


def main(args: argparse.Namespace) -> int:
    name = getattr(args, "scenario", None) or DEMO_SCENARIO
    seed = int(getattr(args, "seed", 0))
    if name not in SCENARIOS:
        raise ScenarioError(f"unknown scenario '{name}' for domain 'namo'; valid scenarios: {', '.join(sorted(SCENARIOS))}")
    spec = SCENARIOS.spec(name)
    fail = getattr(args, "failure_prob", None)
    if fail is not None:
        spec = replace(spec, noise=replace(spec.noise, grasp_fail=float(fail)))
    ep = episode(spec, seed)
    out = Path(getattr(args, "out", None) or "out/demo/namo")
    out.mkdir(parents=True, exist_ok=True)
    strategy = parse_strategy(DEMO_STRATEGY, max_actions=spec.max_actions, time_limit=300.0)
    print(f"nowplan demo namo: {ep.description}")
    print(f"strategy: {DEMO_STRATEGY}; grasp failure probability {spec.noise.grasp_fail:g}\n")
    trace_path = out / "trace.jsonl"
    with Trace(trace_path) as trace:
        metrics, pngs = run_recorded(ep, strategy, seed=seed, trace=trace)
    frames = out / "frames"
    frames.mkdir(exist_ok=True)
    for old in frames.glob("frame-*.png"):
        old.unlink()
    for i, png in enumerate(pngs):
        (frames / f"frame-{i:03d}.png").write_bytes(png)
    gif = out / "namo.gif"
    write_gif(pngs, gif)
    print(metrics.summary())
    looks = sum(v for k, v in metrics.action_counts.items() if k.startswith("Look"))
    picks = metrics.action_counts["Pick"] + metrics.action_counts["Place"]
    print(f"picks/places: {picks}, looks: {looks}, moves: {metrics.action_counts['Move']}")
    print(f"\ntrace: {trace_path}\nframes: {frames} ({len(pngs)} PNG)\nanimation: {gif}")
    try:
        from nowplan.viz.viewer import write_viewer

        page = out / "trace.html"
        write_viewer(trace_path, page)
        print(f"viewer: {page} (open it in a browser)")
    except ImportError as exc:  # pragma: no cover - the viewer is part of the package
        log.warning("no viewer: %s", exc)
    return 0 if metrics.outcome.value == "reached" else 1
