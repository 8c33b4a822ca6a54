"""Why "no plan for the goal": the goal atoms that have no plan even alone (a dead end's place).

A search that exhausts its space says only "unsolvable"; a run that ends there (a tank that
leaked after its one refill was spent, in a held-out greenhouse: benchmarks/results/heldout12)
should say which part of the goal can no longer be reached.  Asked once, when a run gives up on
an unsolvable goal: each unmet atom is planned for alone, concretely, within a small budget.
"""

from __future__ import annotations

import time
from collections.abc import Hashable
from typing import TYPE_CHECKING, Any

from nowplan.acting.metrics import Outcome
from nowplan.acting.refine_flat import flat_hint
from nowplan.core.atoms import Goal
from nowplan.core.levels import flat_levels
from nowplan.errors import NowplanError
from nowplan.planning.config import PlannerConfig
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import concrete, plan

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive
    from nowplan.core.levels import LevelMap

MAX_ATOMS = 8  # unmet goal atoms tried, at most
TIME_EACH = 0.5  # planner seconds per atom
TIME_ALL = 2.0  # seconds for all of them


def unreachable_alone(problem: Any, belief: Any) -> str:
    """``"; no plan even for watered(p2) alone"`` (the atoms whose own search is exhausted), or ``""``."""
    domain, t0 = problem.domain, time.perf_counter()
    dead: list[str] = []
    unmet = [a for a in problem.goal if not domain.holds(a, belief)][:MAX_ATOMS]
    for a in unmet:
        left = TIME_ALL - (time.perf_counter() - t0)
        if left <= 0.05:
            break
        cfg = PlannerConfig(time_limit=min(TIME_EACH, left), relevant_to=problem.goal)
        try:
            res = plan(domain, problem.objects, belief, Goal.of([a], domain.rules), flat_levels(), cfg)
        except NowplanError:  # (a model the flat regression cannot plan: the run's own reason stands)
            return ""
        if res.status is PlanStatus.UNSOLVABLE:
            dead.append(str(a))
    if not dead or len(dead) == len(unmet) > 1:
        return ""  # nothing singled out (or every atom: the search says no more than that)
    return f"; no plan even for {' & '.join(dead)} alone"


def root_failure(ex: Executive, levels: LevelMap, key: Hashable, timed_out: bool) -> tuple[Outcome, str]:
    """How a run ends when the root has no plan at ``levels`` (the last resort declined): the planner's
    reason, what to try for a hierarchy (``flat_hint``), the goal atoms unreachable even alone."""
    outcome = Outcome.LIMIT if timed_out else Outcome.FAILED
    reason = f"no plan for the goal ({ex._last_failure}){ex.model_hint}"
    if not concrete(ex.domain, levels):
        reason += flat_hint(ex, key)
    if ex._last_status is PlanStatus.UNSOLVABLE:
        reason += unreachable_alone(ex.problem, ex.belief)
    if timed_out and ex.remaining_time() <= 0.05:
        # the planner's limit was what remained of the run's: say so, not the clamped figure (a
        # held-out drone run said "time limit of 0.19 s" in a 20 s run)
        reason = (f"time limit of {ex.strategy.time_limit:g} s for the run reached while planning "
                  f"({ex.metrics.world_summary()})")
    return outcome, reason
