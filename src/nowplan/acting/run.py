"""Run one episode (problem, world, belief) under a strategy, with a trace."""

from __future__ import annotations

import gc
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from nowplan import __version__
from nowplan.acting.hpn import Executive
from nowplan.acting.metrics import Metrics
from nowplan.core.operators import Action
from nowplan.acting.strategy import Strategy, is_online
from nowplan.domains.registry import Episode
from nowplan.trace import Trace

if TYPE_CHECKING:
    from nowplan.acting.online import OnlinePolicy


def _frame(trace: Trace, render: Callable[[Any, Any], bytes], episode: Episode, n: int, caption: str) -> None:
    import base64  # frames only (start-up)

    png = render(episode.world, episode.belief)
    uri = "data:image/png;base64," + base64.b64encode(png).decode("ascii")
    trace.emit("frame", n=n, image=uri, caption=caption)


def make_runner(
    episode: Episode,
    strategy: Strategy,
    seed: int = 0,
    trace: Trace | None = None,
    on_action: Callable[[Any, Action], None] | None = None,
) -> Executive | OnlinePolicy:
    """The executive that runs ``episode`` under ``strategy`` (seed 004's online policy for the switches
    online / reuse / deferred, else the plan-stack executive), built but not run: building it refuses a
    strategy the domain or its belief cannot support (a sweep checks its runs this way before any runs)."""
    if is_online(strategy):
        from nowplan.acting.online import OnlinePolicy  # imported for online strategies only (start-up)

        return OnlinePolicy(episode.problem, episode.world, episode.belief, strategy, seed=seed, trace=trace,
                            on_action=on_action)
    return Executive(episode.problem, episode.world, episode.belief, strategy, seed=seed, trace=trace,
                     on_action=on_action)


def run_episode(
    episode: Episode,
    strategy: Strategy,
    seed: int = 0,
    trace: Trace | None = None,
    render: Callable[[Any, Any], bytes] | None = None,
    every: int = 1,
) -> Metrics:
    """Plan, act, observe and update until the goal holds or a budget runs out.

    With ``render`` (a domain's ``(world, belief) -> PNG`` renderer), a
    ``frame`` event is traced at the start, after every ``every``-th action
    and at the end, so the viewer shows the run.
    """
    trace = trace or Trace()
    p = episode.problem
    trace.emit(
        "run_start", domain=p.domain.name, problem=p.name, strategy=strategy.to_dict(), seed=seed,
        goal=[str(a) for a in p.goal], version=__version__, description=episode.description,
    )
    on_action = None
    if render is not None:
        _frame(trace, render, episode, 0, "start")
        step = max(1, every)

        def on_action(ex: Any, action: Action) -> None:  # an Executive or an OnlinePolicy
            if ex.metrics.actions % step == 0:
                _frame(trace, render, episode, ex.metrics.actions, f"after {action.pddl()}")

    runner = make_runner(episode, strategy, seed, trace, on_action)
    # the problem, its groundings and the states made before the run (often most of the heap) are
    # moved out of the collector's generations while it runs: they outlive it, and the collector's
    # passes that the run's own allocations trigger would walk them again and again (miconic
    # 150 floors, --criticality auto: 0.8 s of a 2.5 s run in collections before, see
    # benchmarks/results/criticality_auto_*); a caller's own freeze is left as it is
    freeze = gc.get_freeze_count() == 0
    if freeze:
        gc.freeze()
    try:
        metrics = runner.run()
    finally:
        if freeze:
            gc.unfreeze()
    if render is not None and metrics.actions % max(1, every) != 0:
        _frame(trace, render, episode, metrics.actions, f"end: {metrics.outcome.value}")
    trace.emit("run_end", outcome=metrics.outcome.value, reason=metrics.reason, metrics=metrics.to_dict())
    return metrics
