"""The HPN executive (seed 002 Alg. 1) as a plan stack (seed 000 Fig. 2).

Alg. 1 is recursive: plan at level α, then for each step execute it if it is
concrete, else call HPN on its pre-image goal at ``NextLevel(α, ω)``.  The
plan stack is the same recursion made explicit and bounded: the top plan is
*applicable* while its next step's pre-image ``g_i`` holds in the belief;
``nextStep`` returns ``(ω_{i+1}, g_{i+1})``; an abstract step pushes a plan
for ``g_{i+1}`` one level deeper; a primitive one is executed and the belief
updated.  A plan that is no longer applicable is popped, so a failed action
sends control up to the nearest plan whose pre-image still holds, which is
HPN's failure-driven replanning.  The root plan ``[(None, True), (None, γ)]``
replans γ from scratch until it holds.
"""

from __future__ import annotations

import logging
import random
import time
from collections import Counter
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field
from typing import Any

from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.strategy import Strategy, check_supported
from nowplan.core.atoms import TRUE, Goal
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action
from nowplan.errors import ScenarioError
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.regression import plan as regression_plan
from nowplan.trace import Trace
from nowplan.worlds.base import World

log = logging.getLogger(__name__)


@dataclass
class Frame:
    """A plan on the stack, with the index of the last step taken."""

    plan: Plan
    plan_id: int
    parent: int | None
    parent_step: int | None
    i: int = 0
    root: bool = False
    info: dict[str, Any] = field(default_factory=dict)

    @property
    def n(self) -> int:
        return len(self.plan)


class Executive:
    """Runs one problem to the end under a strategy; see :func:`nowplan.acting.run.run_episode`."""

    def __init__(
        self,
        problem: Problem,
        world: World,
        belief: Any,
        strategy: Strategy,
        *,
        seed: int = 0,
        trace: Trace | None = None,
        on_action: Callable[[Executive, Action], None] | None = None,
    ) -> None:
        self.problem = problem
        self.domain = problem.domain
        self.world = world
        self.belief = belief
        self.strategy = strategy
        self.rng = random.Random(seed)
        self.trace = trace or Trace()
        self.metrics = Metrics()
        self.stack: list[Frame] = []
        self._next_id = 0
        self._pending_trigger: str | None = None
        self._pending_reason = ""
        self.serendipity_events = 0
        self._last_status: PlanStatus | None = None
        self._last_failure = ""
        self._made: dict[int, dict[str, Any]] = {}  # plans made but not pushed yet
        self.mechanisms = strategy.mechanisms()
        self.on_action = on_action  # observers (e.g. a renderer); never change control flow
        # refinements of each step of each plan (by content, see refinement_key) since the last
        # action: the bound on re-planning a step that keeps failing while the belief does not change
        self._refinements: Counter[Hashable] = Counter()
        check_supported(self.domain, strategy)
        if strategy.domain_planner and self.domain.planner is None:
            raise ScenarioError(
                f"domain {self.domain.name} has no planner of its own; "
                "drop the 'domain-planner' switch from the strategy"
            )
        self._planner: Callable[..., PlanResult] = (
            self.domain.planner if self.domain.planner is not None and strategy.domain_planner
            else regression_plan
        )
        self.base_levels = (
            LevelMap(self.domain.top_level) if strategy.hierarchical else flat_levels()
        )

    # -- plan-stack operations ------------------------------------------------
    def applicable(self, f: Frame) -> bool:
        for m in self.mechanisms:
            verdict = m.applicable(self, f)
            if verdict is not None:
                return verdict
        if f.root:
            return not self.domain.satisfies(self.belief, self.problem.goal)
        return f.i < f.n and self.domain.satisfies(self.belief, f.plan.preimage(f.i))

    def next_step(self, f: Frame) -> PlanStep:
        if f.root:
            return f.plan.steps[1]
        for m in self.mechanisms:
            chosen = m.next_step(self, f)
            if chosen is not None:
                return chosen
        f.i += 1
        return f.plan.steps[f.i]

    def push(self, plan: Plan, parent: Frame | None, root: bool = False) -> Frame:
        fr = Frame(
            plan,
            self._next_id,
            parent.plan_id if parent else None,
            parent.i if parent else None,
            root=root,
        )
        fr.info["step_costs"] = [
            s.action.cost(self.belief) if s.action is not None else 0.0 for s in plan.steps
        ]
        self._next_id += 1
        meta = self._made.pop(id(plan), None)
        if meta is not None:
            self.trace.emit(
                "plan", plan_id=fr.plan_id, parent=fr.parent, parent_step=fr.parent_step,
                goal=[str(a) for a in plan.goal], levels=plan.levels.top,
                cost=sum(fr.info["step_costs"]), steps=plan.to_json(), **meta,
            )
        self.stack.append(fr)
        self.trace.emit("push", plan_id=fr.plan_id, depth=len(self.stack))
        for m in self.mechanisms:
            m.after_push(self, fr)
        return fr

    def pop(self, reason: str) -> Frame:
        f = self.stack.pop()
        self.trace.emit("pop", plan_id=f.plan_id, reason=reason)
        if reason in ("not applicable", "failed") and not f.root:
            self._pending_trigger = self._pending_trigger or "failure"
        return f

    def context(self) -> PlanningContext:
        """What the planner and generators see: the plan stack only with foresight on."""
        if self.strategy.foresight:
            return PlanningContext(tuple(f.plan for f in self.stack), {"foresight": True})
        return PlanningContext((), {"foresight": False})

    # -- planning --------------------------------------------------------------
    def make_plan(self, goal: Goal, levels: LevelMap, parent: Frame) -> Plan | None:
        """Plan for ``goal`` at ``levels`` from the current belief; ``None`` on failure (traced)."""
        if self._pending_trigger is not None:
            self.metrics.replans += 1
            self.trace.emit(
                "replan", plan_id=parent.plan_id, trigger=self._pending_trigger,
                reason=self._pending_reason or "a plan was popped before finishing",
            )
            self._pending_trigger = None
            self._pending_reason = ""
        remaining = self.strategy.time_limit - (time.perf_counter() - self._t0)
        cfg = self.strategy.planner
        for m in self.mechanisms:
            cfg = m.planner_config(self, parent, goal, cfg) or cfg
        if remaining < cfg.time_limit:
            from dataclasses import replace

            cfg = replace(cfg, time_limit=max(remaining, 0.01))
        res = self._planner(
            self.domain, self.problem.objects, self.belief, goal, levels, cfg,
            self.context(), self.rng,
        )
        self.metrics.planning_cpu_s += res.cpu_time_s
        if not res.solved or res.plan is None:
            self.metrics.plan_failures += 1
            self.trace.emit(
                "plan_failed", parent=parent.plan_id, parent_step=parent.i,
                goal=[str(a) for a in goal], status=res.status.value, reason=res.reason,
                cpu_s=round(res.cpu_time_s, 6),
            )
            self._last_failure = f"{res.status.value}: {res.reason}"
            self._last_status = res.status
            for m in self.mechanisms:
                m.after_plan_failure(self, parent, goal, res)
            return None
        self.metrics.plans_made += 1
        self._made[id(res.plan)] = {
            "method": res.method, "cpu_s": round(res.cpu_time_s, 6), "expanded": res.expanded,
        }
        return res.plan

    # -- acting ----------------------------------------------------------------
    def execute(self, f: Frame, action: Action) -> None:
        cost = action.cost(self.belief)
        self.trace.emit(
            "action", plan_id=f.plan_id, index=f.i, action=action.pddl(), cost=cost,
            n=self.metrics.actions,
        )
        obs = self.world.execute(action)
        self.metrics.actions += 1
        self.metrics.action_counts[action.name] += 1
        self.metrics.execution_cost += cost
        self.belief.update(action, obs)
        self._refinements.clear()
        self.trace.emit(
            "observation", n=self.metrics.actions - 1, action=action.pddl(), success=obs.success,
            observation=obs.info or None,
        )
        if obs.exogenous:
            self.trace.emit("exogenous", n=self.metrics.actions - 1, change=list(obs.exogenous))
        if self.on_action is not None:
            self.on_action(self, action)
        if not obs.success or not self.domain.satisfies(self.belief, f.plan.preimage(f.i)):
            self.trace.emit(
                "failure", plan_id=f.plan_id, index=f.i, action=action.pddl(),
                reason=str(obs.info.get("reason", "expected result does not hold")),
            )

    def reconsider(self) -> None:
        """After each action, every mechanism may reconsider the plan stack (seed 000 Fig. 2, line 14)."""
        for m in self.mechanisms:
            m.after_action(self)

    def request_replan(self, trigger: str, reason: str) -> None:
        """Mark the next plan made as a replan, with what triggered it."""
        self._pending_trigger = trigger
        self._pending_reason = reason

    def goal_holds(self) -> bool:
        return self.domain.satisfies(self.belief, self.problem.goal)

    @staticmethod
    def refinement_key(f: Frame) -> Hashable:
        """What the loop guard counts refinements of: a step of a plan *by content*.

        A plan that fails is often replanned into the very same plan (the belief has not
        changed); counting per plan id would give every copy a fresh allowance, and the
        allowances multiply down the levels of the stack.  Counting per content bounds the
        refinements of one step of one plan, however often it is remade, until the next action.
        """
        if f.root:
            return ("root", 1)
        acts = tuple(s.action.key if s.action is not None else None for s in f.plan.steps)
        return (acts, f.plan.goal, f.i)

    # -- the loop ------------------------------------------------------------------
    def run(self) -> Metrics:
        self._t0 = time.perf_counter()
        self._last_failure = ""
        self._last_status = None
        goal = self.problem.goal
        root_plan = Plan((PlanStep(None, TRUE), PlanStep(None, goal)), self.base_levels)
        self.push(root_plan, None, root=True)
        outcome, reason = Outcome.REACHED, ""
        consecutive_failures = 0
        while self.stack:
            over = self.strategy.exhausted(self.metrics, time.perf_counter() - self._t0)
            if over is not None:
                outcome, reason = over
                break
            f = self.stack[-1]
            if not self.applicable(f):
                done = self.domain.satisfies(self.belief, f.plan.goal)
                self.pop("done" if done else "not applicable")
                continue
            step = self.next_step(f)
            action = step.action
            self.trace.emit(
                "step", plan_id=f.plan_id, index=f.i if not f.root else 1,
                action=action.pddl() if action is not None else None,
                primitive=bool(action is not None and f.plan.levels.is_primitive(action)),
            )
            if action is None or not f.plan.levels.is_primitive(action):
                if len(self.stack) >= self.strategy.max_depth:
                    outcome, reason = Outcome.LIMIT, f"plan stack deeper than {self.strategy.max_depth}"
                    break
                key = self.refinement_key(f)
                self._refinements[key] += 1
                if self._refinements[key] > self.strategy.max_refinements:
                    why = (
                        f"step {f.i if not f.root else 1} of plan {f.plan_id} (or of identical plans "
                        f"made for it) refined {self.strategy.max_refinements} times without an action "
                        "in between"
                    )
                    if f.root:
                        outcome, reason = Outcome.FAILED, f"no progress: {why}"
                        break
                    self.trace.emit("note", plan_id=f.plan_id, text=f"executive: gave up: {why}")
                    self.pop("failed")
                    continue
                levels = f.plan.levels if action is None else f.plan.levels.next_level(action)
                if f.root:
                    levels = self.base_levels
                new = self.make_plan(step.goal, levels, f)
                if new is None:
                    consecutive_failures += 1
                    if f.root:
                        timed_out = self._last_status is PlanStatus.TIME_LIMIT
                        outcome = Outcome.LIMIT if timed_out else Outcome.FAILED
                        reason = f"no plan for the goal ({self._last_failure})"
                        break
                    if consecutive_failures > 3 * self.strategy.max_depth:
                        outcome, reason = Outcome.FAILED, f"repeated planning failures ({self._last_failure})"
                        break
                    self.pop("failed")  # the refined step cannot be achieved from here
                    continue
                consecutive_failures = 0
                self.push(new, f)
            else:
                self.execute(f, action)
                self.reconsider()
        if outcome is Outcome.REACHED and not self.goal_holds():
            outcome, reason = Outcome.FAILED, "plan stack emptied before the goal held"
        self.metrics.outcome = outcome
        self.metrics.reason = reason
        self.metrics.wall_s = time.perf_counter() - self._t0
        return self.metrics
