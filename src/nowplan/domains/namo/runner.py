"""Running NAMO episodes with pictures: trace ``frame`` events and GIF frames.

:func:`run_recorded` is :func:`nowplan.acting.run.run_episode` with an
executive that, after every ``every``-th action, renders the world, the
belief and the plans on the stack (their moves' swept volumes, planned
manipulation paths; the route of the previous outermost plan in grey) and
emits the picture as a trace ``frame`` event (a PNG data URI the trace
viewer embeds).
"""

from __future__ import annotations

import base64
from dataclasses import dataclass, field
from typing import Any

from nowplan import __version__
from nowplan.acting.hpn import Executive, Frame
from nowplan.acting.metrics import Metrics
from nowplan.acting.strategy import Strategy
from nowplan.core.operators import Action
from nowplan.domains.namo.geometry import Manip, Pt, Region
from nowplan.domains.namo.render import render_png
from nowplan.domains.registry import Episode
from nowplan.trace import Trace


def stack_regions(ex: Executive) -> list[Region]:
    out: dict[Region, None] = {}
    for f in ex.stack:
        for a in f.plan.actions:
            if a.name == "Move" and isinstance(a.args[2], Region):
                out[a.args[2]] = None
    return list(out)


def route_of(plan: Any) -> list[Pt]:
    regions = [a.args[2] for a in plan.actions if a.name == "Move" and isinstance(a.args[2], Region)]
    if not regions:
        return []
    return [regions[0].start, *(r.end for r in regions)]


def stack_manips(ex: Executive) -> list[Manip]:
    out: dict[Manip, None] = {}
    for f in ex.stack:
        for a in f.plan.actions:
            if a.name == "Place" and isinstance(a.args[4], Manip):
                out[a.args[4]] = None
    return list(out)


@dataclass
class Recorder:
    every: int = 1
    dpi: int = 80
    pngs: list[bytes] = field(default_factory=list)
    old_routes: list[list[Pt]] = field(default_factory=list)
    _outer: Any = None


class RecordingExecutive(Executive):
    """An executive that renders a frame after actions (the engine's loop is unchanged)."""

    recorder: Recorder

    def snapshot(self, caption: str) -> None:
        rec = self.recorder
        outer = self.stack[1].plan if len(self.stack) > 1 else None
        if outer is not None and rec._outer is not None and outer is not rec._outer:
            old = route_of(rec._outer)
            new = route_of(outer)
            if old and old != new:
                rec.old_routes = [old]
        if outer is not None:
            rec._outer = outer
        goal = next((a.args[0] for a in self.problem.goal.atoms
                     if a.predicate == "RobotAt" and isinstance(a.args[0], Pt)), None)
        png = render_png(
            self.world, self.belief, stack_regions(self), rec.old_routes, stack_manips(self), goal,
            caption, rec.dpi,
        )
        rec.pngs.append(png)
        uri = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
        self.trace.emit("frame", n=self.metrics.actions, image=uri, caption=caption)

    def execute(self, f: Frame, action: Action) -> None:
        super().execute(f, action)
        n = self.metrics.actions
        if n % max(self.recorder.every, 1) == 0:
            self.snapshot(f"after action {n}: {action.name}")


def run_recorded(
    episode: Episode, strategy: Strategy, seed: int = 0, trace: Trace | None = None,
    every: int = 1, dpi: int = 80,
) -> tuple[Metrics, list[bytes]]:
    """Like ``run_episode``, with a frame before the first action and after every ``every`` actions."""
    trace = trace or Trace()
    p = episode.problem
    trace.emit(
        "run_start", domain=p.domain.name, problem=p.name, strategy=strategy.to_dict(), seed=seed,
        goal=[str(a) for a in p.goal], version=__version__, description=episode.description,
    )
    ex = RecordingExecutive(p, episode.world, episode.belief, strategy, seed=seed, trace=trace)
    ex.recorder = Recorder(every=every, dpi=dpi)
    ex.snapshot("start: walls known, obstacles unknown, fog unobserved")
    metrics = ex.run()
    ex.snapshot(f"end: {metrics.outcome.value}")
    trace.emit("run_end", outcome=metrics.outcome.value, reason=metrics.reason, metrics=metrics.to_dict())
    return metrics, ex.recorder.pngs
