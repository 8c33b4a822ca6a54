"""The online replanning policy of seed 004 (SS-Replan, Alg. 1), selectable by switch.

Each iteration *determinizes* the belief problem (the domain's cost
functions read the current belief: self-loop costs of detections and other
stochastic actions), plans, executes only the first action, and updates the
belief.  Two switches make Table I's four variants:

* ``reuse`` — if a previous tail exists, first plan under its constraints
  (Alg. 2, :mod:`nowplan.acting.reuse`) within ``reuse_budget`` seconds, then
  fall back to unconstrained planning;
* ``deferred`` — bind only the hypothetical stream values the first action
  needs (:mod:`nowplan.acting.deferred`); otherwise bind them all.

The policy stops when the goal belief holds (``reached``), when no plan
with expected cost below ``c*`` exists (``failed``, with the planner's
reason), or when a budget runs out (``limit``).  ``online`` alone is the
Neither variant.  The agent's streams come from ``belief.streams`` (a
:class:`~nowplan.planning.streams.StreamSet`), if the belief has any.
"""

from __future__ import annotations

import logging
import math
import random
import time
from collections.abc import Callable, Hashable
from dataclasses import replace
from typing import Any

from nowplan.acting.deferred import resolve
from nowplan.acting.mechanisms import Mechanism, Switch, register_switch
from nowplan.acting.judge import judge
from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.reobserve import look_again
from nowplan.acting.guard import ProgressGuard
from nowplan.acting.dead_end import unreachable_alone
from nowplan.acting.progress import Cycle, start_warnings
from nowplan.acting.reuse import SkeletonStep, constrained_plan, skeleton
from nowplan.acting.strategy import Strategy, check_supported
from nowplan.acting.whole import plan_whole_problem
from nowplan.belief.protocols import check_belief
from nowplan.belief.symbolic import truth_of
from nowplan.belief.protocols import AfterAction, HasHeuristic, HasStreams
from nowplan.core.domain import Problem
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Action
from nowplan.errors import ScenarioError
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import PlanResult, PlanStatus
from nowplan.planning.regression import plan as regression_plan
from nowplan.trace import Trace
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)

class _OnlineOnly(Mechanism):
    """Refuses to run under the plan-stack executive: these switches need the online policy."""

    def __init__(self, strategy: Any) -> None:
        self.name = "online"

    def after_push(self, ex: Any, frame: Any) -> None:
        raise ScenarioError(
            "the switches 'online', 'reuse' and 'deferred' select the online replanning policy; "
            "run them through nowplan.acting.run.run_episode (e.g. strategy 'online+reuse+deferred')"
        )


register_switch(Switch("online", "SS-Replan's online policy: replan after every action (seed 004 Alg. 1)",
                       mechanism=_OnlineOnly))
register_switch(Switch("reuse", "reuse-enforced replanning under the previous plan's skeleton (seed 004 Alg. 2)",
                       mechanism=_OnlineOnly))
register_switch(Switch("deferred", "deferred evaluation of expensive, likely streams (seed 004 VII)",
                       mechanism=_OnlineOnly))


class OnlinePolicy:
    """Runs one problem under Alg. 1; ``reuse_budget`` caps each constrained planning attempt."""

    def __init__(
        self,
        problem: Problem,
        world: Any,
        belief: Any,
        strategy: Strategy,
        *,
        seed: int = 0,
        trace: Trace | None = None,
        c_star: float = math.inf,
        reuse_budget: float = 2.0,
        max_resolve_retries: int = 4,
        on_action: Callable[[Any, Action], None] | None = None,
    ) -> None:
        check_supported(problem.domain, strategy)
        check_belief(problem.domain, belief)
        self.model_hint = start_warnings(problem, belief)  # (logged; "no plan for the goal" repeats it)
        self.problem = problem
        self.on_action = on_action  # observers (e.g. a renderer); never change control flow
        self.domain = problem.domain
        self.world = world
        self.belief = belief
        self.strategy = strategy
        self.reuse = "reuse" in strategy.switches
        self.deferred = "deferred" in strategy.switches
        self.c_star = c_star
        self.reuse_budget = reuse_budget
        self.max_resolve_retries = max_resolve_retries
        self.rng = random.Random(seed)
        # the planning cap's clock: the planner's (``PlannerConfig.clock``: wall, or this process's CPU
        # time, which a machine shared with other jobs does not inflate)
        self.clock: Callable[[], float] = time.process_time if strategy.planner.clock == "cpu" else time.perf_counter
        self.trace = trace or Trace()
        self.metrics = Metrics()
        self.streams = belief.streams if isinstance(belief, HasStreams) else None
        self.levels = flat_levels()
        self._tail: list[Action] = []  # after a cycle: the rest of the plan committed to
        # the progress guard (acting/guard.py), shared with the plan-stack executive: progress (a
        # belief never held before, reached while committed) ends a commitment's count of cycles;
        # without it, cycles made before and after a long stretch of progress added up to a
        # livelock (a held-out lab domain, online, seed 12)
        self.guard = ProgressGuard(strategy.max_cycles)
        self.last_action: Action | None = None
        self.last_failed: tuple[Action, Observation] | None = None  # the last action that failed
        self._acting: list[Action] = []  # the plan whose first action was just executed
        self._acted_ok = True  # whether that action succeeded
        self.planning_s = 0.0  # time (on :attr:`clock`) spent planning and binding streams
        self.constrained_ok = 0
        self.constrained_tried = 0
        self._plan_id = 0

    # -- one planning call -------------------------------------------------------
    def _plan(self, prev: tuple[SkeletonStep, ...] | None, deadline: float) -> PlanResult:
        goal = self.problem.goal
        # a domain may offer its own goal-distance estimate through the belief (regression's hook)
        h = self.belief.planning_heuristic if isinstance(self.belief, HasHeuristic) else None
        ctx = PlanningContext((), {"online": True, "heuristic": h, "whole_problem": True})
        if self.reuse and prev:
            self.constrained_tried += 1
            budget = max(min(self.reuse_budget, deadline - self.clock()), 0.01)
            res = constrained_plan(
                self.domain, self.problem.objects, self.belief, goal, prev, budget, ctx,
                self.strategy.planner.max_generator_values, clock=self.clock,
            )
            if res.solved:
                self.constrained_ok += 1
                return res
            self.trace.emit("note", text=f"constrained replanning failed ({res.reason}); unconstrained")
        base = self.strategy.planner
        if self.streams is not None:
            self.streams.reset_level()
        while True:
            level = self.streams.level if self.streams is not None else 1
            cfg = replace(base, max_generator_values=base.max_generator_values * level)
            remaining = deadline - self.clock()
            if remaining < cfg.time_limit:
                cfg = replace(cfg, time_limit=max(remaining, 0.01))
            res = plan_whole_problem(
                regression_plan, self.domain, self.problem.objects, self.belief, goal, self.levels, cfg, ctx, self.rng
            )
            # adaptive sampling: a search that ran out of candidates gets larger sample pools
            if res.solved or res.status is PlanStatus.TIME_LIMIT or self.streams is None or not self.streams.grow():
                return res
            self.trace.emit("note", text=f"planning failed ({res.reason}); sample pools grow")

    def _act(self, first: Action, plan_id: int) -> Observation:
        """Execute one action, update the belief, trace both."""
        self.trace.emit("action", plan_id=plan_id, index=1, action=first.pddl(),
                        cost=first.cost(self.belief), n=self.metrics.actions)
        obs: Observation = self.world.execute(first)
        self.metrics.actions += 1
        self.last_action = first
        if not obs.success:
            self.last_failed = (first, obs)
        self.metrics.action_counts[first.name] += 1
        self.metrics.execution_cost += first.cost(self.belief)
        self.belief.update(first, obs)
        self.metrics.failed_actions += not obs.success
        self.metrics.exogenous_changes += bool(obs.exogenous)
        self.trace.emit("observation", n=self.metrics.actions - 1, action=first.pddl(),
                        success=obs.success, observation=obs.info or None)
        if obs.exogenous:
            self.trace.emit("exogenous", n=self.metrics.actions - 1, change=list(obs.exogenous))
        if isinstance(self.belief, AfterAction) and self.belief.after_action is not None:
            self.belief.after_action(self.trace, first, obs)
        if self.on_action is not None:
            self.on_action(self, first)
        return obs

    # -- the progress guard's host (acting/guard.py) ------------------------------------------
    @property
    def truth(self) -> Any:
        """What the goal tests read (:func:`~nowplan.belief.symbolic.truth_of`)."""
        return truth_of(self.domain, self.belief)

    def situation(self) -> Hashable | None:
        """The belief's fingerprint and the goal."""
        return self.guard.situation(self, self.belief, (self.problem.goal,))

    actor = "the policy"  # who had committed, in a livelock's reason

    def after_cycle(self, cyc: Cycle) -> None:
        """A cycle closed: nothing to tell (the policy has no reconsidering mechanisms)."""

    def commit(self, cyc: Cycle) -> str:
        """Commit to the rest of the plan just acted on instead of replanning after every action."""
        plan = self._acting
        self._tail = plan[1:] if self._acted_ok else plan  # a failed first action is tried again
        return (f"committing to the current plan ({len(self._tail)} action(s)) instead of replanning after "
                "every action")

    def end_commitment(self) -> str:
        # the guard's count restarts; the rest of the plan committed to is still followed (see _committed_step)
        return "the count of cycles restarts"

    def _watch(self, obs: Observation, plan: list[Action]) -> tuple[Outcome, str] | None:
        """The progress guard after ``plan``'s first action: commit to its rest on a cycle; the run's end."""
        self._acting = plan
        self._acted_ok = obs.success
        return self.guard.watch(self, obs)

    def _budget_left(self, t0: float) -> tuple[Outcome, str] | None:
        return self.strategy.exhausted(self.metrics, self.clock() - t0)

    def _committed_step(self) -> Action | None:
        """After a cycle: the next action of the plan committed to, while its preconditions hold."""
        if not self._tail:
            return None
        nxt = self._tail[0]
        if all(self.domain.holds(a, self.belief) for a in nxt.preconditions(None)):
            return nxt
        self._tail = []
        self.trace.emit("note", text="progress: commitment ends (the committed plan's next step is not applicable)")
        return None

    def run(self) -> Metrics:
        t0 = self.clock()
        wall0 = time.perf_counter()
        deadline = t0 + self.strategy.time_limit
        prev: tuple[SkeletonStep, ...] | None = None
        outcome, reason = Outcome.FAILED, ""
        retries = 0
        looks = 0  # fresh looks since the last plan (acting/reobserve.py)
        self._tail = []
        self.guard.start(self)
        while True:
            if self.domain.satisfies(self.belief, self.problem.goal):
                outcome, reason = Outcome.REACHED, ""
                break
            over = self._budget_left(t0)
            if over is not None:
                outcome, reason = over
                break
            committed = self._committed_step()
            if committed is not None:
                rest = self._tail[1:]
                obs = self._act(committed, self._plan_id - 1)
                # a failed step is retried while its preconditions hold
                self._tail = rest if obs.success else [committed, *rest]
                stop = self._watch(obs, [committed, *rest])
                if stop is not None:
                    outcome, reason = stop
                    break
                prev = None
                continue
            tp = self.clock()
            res = self._plan(prev, deadline)
            self.metrics.planning_cpu_s += res.cpu_time_s
            if not res.solved or res.plan is None:
                self.planning_s += self.clock() - tp
                self.metrics.plan_failures += 1
                self.trace.emit("plan_failed", parent=None, parent_step=None,
                                goal=[str(a) for a in self.problem.goal], status=res.status.value,
                                reason=res.reason, cpu_s=round(res.cpu_time_s, 6))
                timed = res.status is PlanStatus.TIME_LIMIT
                if not timed and look_again(self.belief, self.trace, looks, f"{res.status.value}: {res.reason}"):
                    looks += 1
                    prev = None
                    continue
                outcome = Outcome.LIMIT if timed else Outcome.FAILED
                reason = f"no plan for the goal ({res.status.value}: {res.reason}){self.model_hint}"
                if res.status is PlanStatus.UNSOLVABLE:
                    reason += unreachable_alone(self.problem, self.belief)
                if timed and self.clock() - t0 >= self.strategy.time_limit - 0.05:
                    # the planner's limit was what remained of the run's: say so, not the clamped figure
                    reason = (f"time limit of {self.strategy.time_limit:g} s for the run reached while planning "
                              f"({self.metrics.world_summary()})")
                break
            cost = res.plan.cost(self.belief)
            if not cost <= self.c_star:
                self.planning_s += self.clock() - tp
                outcome, reason = Outcome.FAILED, f"no plan with expected cost below c*={self.c_star:g} (best {cost:g})"
                break
            actions = res.plan.actions
            looks = 0
            if self.streams is not None:
                rs = resolve(actions, self.streams, self.belief, self.deferred)
                self.planning_s += self.clock() - tp
                if not rs.ok:
                    retries += 1
                    self.metrics.plan_failures += 1
                    self.trace.emit("note", text=f"stream {rs.failed} failed; replanning")
                    prev = None
                    if retries > self.max_resolve_retries:
                        outcome, reason = Outcome.FAILED, f"streams kept failing ({rs.failed})"
                        break
                    continue
                actions = rs.actions
            else:
                self.planning_s += self.clock() - tp
            retries = 0
            self.metrics.plans_made += 1
            if prev is not None:
                self.metrics.replans += 1
            self.trace.emit(
                "plan", plan_id=self._plan_id, parent=None, parent_step=None,
                goal=[str(a) for a in self.problem.goal], levels=0, cost=cost,
                steps=[{"index": i + 1, "action": a.pddl()} for i, a in enumerate(actions)],
                method=res.method, cpu_s=round(res.cpu_time_s, 6), expanded=res.expanded,
            )
            self._plan_id += 1
            first = actions[0]
            obs = self._act(first, self._plan_id - 1)
            stop = self._watch(obs, list(actions))
            if stop is not None:
                outcome, reason = stop
                break
            # Alg. 1 line 17: the unexecuted tail constrains the next plan (if it went as planned)
            prev = skeleton(actions[1:]) if obs.success else None
        self.metrics.outcome = outcome
        self.metrics.reason = reason
        judge(self.domain, self.problem.goal, self.belief, self.world, self.metrics, self.trace)
        self.metrics.wall_s = time.perf_counter() - wall0
        log.info("online policy: %s %s", self.metrics.outcome.value, self.metrics.reason)
        return self.metrics
