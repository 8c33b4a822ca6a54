"""Success judged in the world where the world can tell.

At the end of a run the executive's outcome says whether the goal holds in the
agent's *belief*.  A simulated world that can tell its true state
(:class:`~nowplan.worlds.base.Inspectable`) is asked once more: ``reached`` then
means the goal holds in the world, and the run result names the goal's atoms on
which belief and world disagree.  A run whose belief says "done" while the world
says otherwise ends ``failed`` with that disagreement as its reason.
"""

from __future__ import annotations

import logging
from typing import Any

from nowplan.acting.metrics import Metrics, Outcome
from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.trace import Trace
from nowplan.worlds.base import Inspectable

log = logging.getLogger(__name__)


def disagreement(domain: Domain, goal: Goal, belief: Any, truth: Any) -> tuple[str, ...]:
    """The goal's atoms that hold in exactly one of belief and world, as text, sorted."""
    out = [str(a) for a in goal.atoms if domain.holds(a, belief) != domain.holds(a, truth)]
    return tuple(sorted(out))


def judge(domain: Domain, goal: Goal, belief: Any, world: Any, metrics: Metrics, trace: Trace) -> None:
    """Fill the metrics' world verdict; turn a belief-only success into a failure with its reason."""
    metrics.goal_in_belief = domain.satisfies(belief, goal)
    if not isinstance(world, Inspectable):
        return  # the world cannot tell: the belief's verdict stands
    truth = world.true_state()
    metrics.goal_in_world = domain.satisfies(truth, goal)
    metrics.disagreement = disagreement(domain, goal, belief, truth)
    if metrics.disagreement:
        trace.emit("disagreement", atoms=list(metrics.disagreement),
                   goal_in_belief=metrics.goal_in_belief, goal_in_world=metrics.goal_in_world)
        log.info("belief and world disagree on %s", ", ".join(metrics.disagreement))
    if metrics.outcome is Outcome.REACHED and not metrics.goal_in_world:
        metrics.outcome = Outcome.FAILED
        metrics.reason = (
            "the goal holds in the belief but not in the world (they disagree on "
            + ", ".join(metrics.disagreement) + ")"
        )
