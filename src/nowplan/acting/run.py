"""Run one episode (problem, world, belief) under a strategy, with a trace."""

from __future__ import annotations

from nowplan import __version__
from nowplan.acting.hpn import Executive
from nowplan.acting.metrics import Metrics
from nowplan.acting.strategy import Strategy
from nowplan.domains.registry import Episode
from nowplan.trace import Trace


def run_episode(
    episode: Episode, strategy: Strategy, seed: int = 0, trace: Trace | None = None
) -> Metrics:
    """Plan, act, observe and update until the goal holds or a budget runs out."""
    trace = trace or Trace()
    p = episode.problem
    trace.emit(
        "run_start", domain=p.domain.name, problem=p.name, strategy=strategy.to_dict(), seed=seed,
        goal=[str(a) for a in p.goal], version=__version__, description=episode.description,
    )
    from nowplan.acting.online import OnlinePolicy, is_online

    if is_online(strategy):  # seed 004's online policy (switches online / reuse / deferred)
        metrics = OnlinePolicy(p, episode.world, episode.belief, strategy, seed=seed, trace=trace).run()
    else:
        metrics = Executive(p, episode.world, episode.belief, strategy, seed=seed, trace=trace).run()
    trace.emit("run_end", outcome=metrics.outcome.value, reason=metrics.reason, metrics=metrics.to_dict())
    return metrics
