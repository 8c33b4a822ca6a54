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
from dataclasses import dataclass, field, replace
from typing import Any

from nowplan.acting.judge import judge
from nowplan.acting.backtrack import Nogoods
from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.guard import ProgressGuard
from nowplan.acting.dead_end import root_failure
from nowplan.acting.postpone import postpone
from nowplan.acting.progress import Cycle, start_warnings
from nowplan.acting.reobserve import look_again
from nowplan.acting.refine import Achievers, direct_refinement, refine_without_swaps
from nowplan.acting.refine_flat import FlatSteps, call_config, flat_hint, refinement_key, root_time_share
from nowplan.acting.static_watch import StaticWatch
from nowplan.acting.strategy import Strategy, check_supported
from nowplan.acting.whole import plan_whole_problem
from nowplan.belief.protocols import HasHeuristic, check_belief
from nowplan.belief.symbolic import truth_of
from nowplan.core.atoms import TRUE, Goal
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.errors import ScenarioError
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep, goal_text
from nowplan.planning.regression import concrete
from nowplan.planning.regression import plan as regression_plan
from nowplan.trace import Lazy, Trace
from nowplan.worlds.base import Observation, World

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
        # goals tested in the current truth, while it is one immutable State (holds_goal)
        self._tested: tuple[Any, dict[int, tuple[Goal, bool]]] = (None, {})
        self._atom_text: dict[Any, Any] = {}  # Plan.to_json's, across plans
        self.mechanisms = strategy.mechanisms()
        self.on_action = on_action  # observers (e.g. a renderer); never change control flow
        # refinements of each step of each plan (by content, see refinement_key) since the last
        # action: the bound on re-planning a step that keeps failing while the belief does not change
        self._refinements: Counter[Hashable] = Counter()
        # the progress guard: cycles across actions, and the plan committed to after one
        self.guard = ProgressGuard(strategy.max_cycles)
        self.last_observation = Observation()
        self.last_action: Action | None = None
        self.last_failed: tuple[Action, Observation] | None = None  # the last action that failed
        # refine-flat (acting/refine_flat.py): steps whose goal is planned concretely from then on
        self._flat_steps = FlatSteps()
        # first steps learnt not to be refinable from the current belief (acting/backtrack.py)
        self.nogoods = Nogoods()
        self.achievers = Achievers()  # ground actions by effect, for refinements made directly
        check_supported(self.domain, strategy)
        check_belief(self.domain, belief)
        self._static = StaticWatch(self.domain, belief)  # static facts the world may change (acting/static_watch.py)
        self.model_hint = start_warnings(problem, belief)  # (logged; "no plan for the goal" repeats it)
        for m in self.mechanisms:
            m.check(self)
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
        # a flat strategy, or a domain whose top level keeps every precondition (the kitchen: no
        # criticalities): every call plans the whole problem concretely, as a flat strategy's does
        self.single_level = not strategy.hierarchical or concrete(self.domain, self.base_levels)

    @property
    def truth(self) -> Any:
        """What the executive's own tests of goals read: a symbolic belief's state where the domain's
        truth is plain (``Domain.satisfies`` then looks each atom up in it), else the belief."""
        return truth_of(self.domain, self.belief)

    def holds_goal(self, goal: Goal) -> bool:
        """``Domain.satisfies(truth, goal)``, remembered per goal while the truth is the same State (an
        immutable point state where truth is plain): the loop tests a step's pre-image before and after
        its action, and the frames below (gripper-250 under --criticality auto: 4,002 tests of 2,001
        distinct (state, goal) pairs, each over ~250 atoms)."""
        truth = self.truth
        if not isinstance(truth, State):
            return self.domain.satisfies(truth, goal)
        seen, tested = self._tested
        if seen is not truth:
            tested = {}
            self._tested = (truth, tested)
        hit = tested.get(id(goal))
        if hit is not None and hit[0] is goal:
            return hit[1]
        verdict = self.domain.satisfies(truth, goal)
        tested[id(goal)] = (goal, verdict)  # (the goal is kept: its id is not reused meanwhile)
        return verdict

    # -- plan-stack operations ------------------------------------------------
    def applicable(self, f: Frame) -> bool:
        for m in self.mechanisms:
            verdict = m.applicable(self, f)
            if verdict is not None:
                return verdict
        if f.root:
            return not self.holds_goal(self.problem.goal)
        return f.i < f.n and self.holds_goal(f.plan.preimage(f.i))

    def next_step(self, f: Frame) -> PlanStep:
        if f.root:
            # the first stage (Problem.stages) that does not hold yet, else the goal
            last = len(f.plan.steps) - 1
            for i in range(1, last):
                if not self.holds_goal(f.plan.steps[i].goal):
                    f.i = i
                    return f.plan.steps[i]
            f.i = last
            return f.plan.steps[-1]
        for m in self.mechanisms:
            chosen = m.next_step(self, f)
            if chosen is not None:
                return chosen
        f.i += 1
        return f.plan.steps[f.i]

    def push(self, plan: Plan, parent: Frame | None, root: bool = False) -> Frame:
        if not root and self.strategy.postpone and self.strategy.hierarchical:
            plan = self._postponed(plan)
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
            made = self._atom_text  # (the records are made when the trace is read or written)
            self.trace.emit(
                "plan", plan_id=fr.plan_id, parent=fr.parent, parent_step=fr.parent_step,
                goal=Lazy(lambda: goal_text(plan.goal, made)), levels=plan.levels.top,
                cost=sum(fr.info["step_costs"]), steps=Lazy(lambda: plan.to_json(made)), **meta,
            )
        self.stack.append(fr)
        self.trace.emit("push", plan_id=fr.plan_id, depth=len(self.stack))
        for m in self.mechanisms:
            m.after_push(self, fr)
        return fr

    def _postponed(self, plan: Plan) -> Plan:
        """``plan`` with the goal atoms its steps leave alone owed only at its end (acting/postpone.py)."""
        out, later = postpone(plan, self.domain, self.truth, self.problem.goal)
        if out is not plan:
            meta = self._made.pop(id(plan), None)
            if meta is not None:
                self._made[id(out)] = {**meta, "postponed": goal_text(Goal(later), self._atom_text)}
        return out

    def pop(self, reason: str) -> Frame:
        f = self.stack.pop()
        self.trace.emit("pop", plan_id=f.plan_id, reason=reason)
        if reason in ("not applicable", "failed") and not f.root:
            self._pending_trigger = self._pending_trigger or "failure"
        return f

    def context(self) -> PlanningContext:
        """What the planner and generators see: the plan stack only with foresight on; a flat strategy's
        planner also gets the domain's goal-distance estimate, as the online policy's flat planner does."""
        extras: dict[str, Any] = {"foresight": self.strategy.foresight}
        if self.single_level:  # it plans the whole problem: no level above to fall back to
            extras["whole_problem"] = True
            if isinstance(self.belief, HasHeuristic):
                extras["heuristic"] = self.belief.planning_heuristic
        return PlanningContext(tuple(f.plan for f in self.stack) if self.strategy.foresight else (), extras)

    # -- planning --------------------------------------------------------------
    def reject_plan(self, plan: Plan, parent: Frame, reason: str) -> None:
        """A plan made but not to be pushed (a refinement planned again, acting/refine.py): traced and
        counted as a planner call that gave no plan to push (``plan_failed``, status ``rejected``)."""
        meta = self._made.pop(id(plan), {})
        self.metrics.plans_made -= 1
        self.metrics.plan_failures += 1
        self.metrics.plans_rejected += 1
        self.trace.emit("plan_failed", parent=parent.plan_id, parent_step=parent.i,
                        goal=[str(a) for a in plan.goal], status="rejected", reason=reason,
                        cpu_s=meta.get("cpu_s", 0.0))

    def made_with(self, plan: Plan) -> dict[str, Any]:
        """What the planner reported for a plan made but not pushed yet (method, cpu_s, expanded)."""
        return self._made.get(id(plan), {})

    def make_plan(self, goal: Goal, levels: LevelMap, parent: Frame, max_nodes: int | None = None,
                  time_share: float = 1.0) -> Plan | None:
        """Plan for ``goal`` at ``levels`` from the current belief (at most ``max_nodes`` expansions
        if given, ``time_share`` of the run's remaining time); ``None`` on failure (traced).  Below
        the root, forward searches keep the regression budget (refine_flat.call_config)."""
        if self._pending_trigger is not None:
            self.metrics.replans += 1
            self.trace.emit(
                "replan", plan_id=parent.plan_id, trigger=self._pending_trigger,
                reason=self._pending_reason or "a plan was popped before finishing",
            )
            self._pending_trigger = None
            self._pending_reason = ""
        remaining = self.remaining_time() * time_share
        cfg = self.strategy.planner
        for m in self.mechanisms:
            cfg = m.planner_config(self, parent, goal, cfg) or cfg
        if max_nodes is not None and max_nodes < cfg.max_nodes:
            cfg = replace(cfg, max_nodes=max_nodes, shortcut_nodes=min(cfg.shortcut_nodes, max_nodes))
        cfg = call_config(cfg, parent.root)
        if remaining < cfg.time_limit:
            cfg = replace(cfg, time_limit=max(remaining, 0.01))
        if cfg.relevant_to is None:  # every call serves the problem's goal: ground what it needs, once
            cfg = replace(cfg, relevant_to=self.problem.goal)
        context = self.context()
        forbidden = self.nogoods.forbidden(goal, levels)
        if forbidden:
            context = replace(context, extras={**context.extras, "forbidden_first": forbidden})
            if cfg.regroup:  # a refinement of this goal's plan failed in this belief: the planner's own order
                cfg = replace(cfg, regroup=False)
        if context.whole_problem:  # no level above: the generators' restricted pass comes second
            res = plan_whole_problem(
                self._planner, self.domain, self.problem.objects, self.belief, goal, levels, cfg, context, self.rng,
            )
        else:
            res = self._planner(
                self.domain, self.problem.objects, self.belief, goal, levels, cfg, context, self.rng,
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

    def direct_plan(self, goal: Goal, levels: LevelMap, action: Action, may_swap: bool = False) -> Plan | None:
        """A refinement of ``action`` made without a planner call (acting/refine.py), counted as a
        plan made (method ``direct``); ``None``: the planner refines the step.  ``may_swap``: the step
        was not itself swapped in, so its refinement may swap it for a sibling (as a planner's may)."""
        t0 = time.process_time()
        plan = direct_refinement(self, goal, levels, action, may_swap)
        cpu = time.process_time() - t0
        self.metrics.planning_cpu_s += cpu
        if plan is not None:
            self.metrics.plans_made += 1
            self._made[id(plan)] = {"method": "direct", "cpu_s": round(cpu, 6), "expanded": 0}
        return plan

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
        self.metrics.failed_actions += not obs.success
        self.metrics.exogenous_changes += bool(obs.exogenous)
        self._refinements.clear()
        self.nogoods.clear()
        self.trace.emit(
            "observation", n=self.metrics.actions - 1, action=action.pddl(), success=obs.success,
            observation=obs.info or None,
        )
        if obs.exogenous:
            self.trace.emit("exogenous", n=self.metrics.actions - 1, change=list(obs.exogenous))
        if self.on_action is not None:
            self.on_action(self, action)
        if not obs.success or not self.holds_goal(f.plan.preimage(f.i)):
            self.trace.emit(
                "failure", plan_id=f.plan_id, index=f.i, action=action.pddl(),
                reason=str(obs.info.get("reason", "expected result does not hold")),
            )
        self.last_observation = obs
        self.last_action = action
        if not obs.success:
            self.last_failed = (action, obs)
        self._static.after_observation(self, bool(obs.exogenous))  # a static fact the world changed

    def backtrack(self, f: Frame, action: Action | None) -> None:
        """No plan refines ``f``'s current step: learn it as a nogood and re-refine one level up.

        The step's action may not start a plan for ``f``'s goal at ``f``'s levels
        until the next action; ``f`` is popped and its parent is set back to
        the step ``f`` refined, so that step is planned again with the nogood
        (acting/backtrack.py) instead of being re-issued as it was.
        """
        if action is not None:
            self.nogoods.learn(f.plan.goal, f.plan.levels, action.key)
            self.trace.emit("note", plan_id=f.plan_id,
                            text=f"backtrack: {action.pddl()} cannot be refined here; replanning the level above")
            if self._flat_steps.after_backtrack(self, (f.plan.goal, f.plan.levels, action.key), action.pddl()):
                return  # refined in vain again and again: the root goal is planned concretely
        self.unwind(len(self.stack) - 1, "failed")

    def unwind(self, depth: int, reason: str) -> None:
        """Pop the plans from ``depth`` up (``reason``) and set the plan below back to the step they
        refined, so that step is planned again (a backtrack; a static fact the world changed)."""
        while len(self.stack) > depth:
            self.pop(reason)
        parent = self.stack[-1] if self.stack else None
        if parent is not None and not parent.root and parent.i > 0:
            parent.i -= 1

    def reconsider(self) -> None:
        """After each action, every mechanism may reconsider the plan stack (seed 000 Fig. 2, line 14)."""
        for m in self.mechanisms:
            m.after_action(self)

    def remaining_time(self) -> float:
        """Seconds left of the run's time budget (for planner calls made outside ``make_plan``)."""
        return self.strategy.time_limit - (time.perf_counter() - self._t0)

    def request_replan(self, trigger: str, reason: str) -> None:
        """Mark the next plan made as a replan, with what triggered it."""
        self._pending_trigger = trigger
        self._pending_reason = reason

    # -- the progress guard's host (acting/guard.py) ------------------------------------
    actor = "the executive"  # who had committed, in a livelock's reason

    @property
    def committed(self) -> bool:
        """After a cycle: reconsidering mechanisms keep the current plans until there is progress."""
        return self.guard.committed

    def situation(self) -> Hashable | None:
        """The belief's fingerprint and the plan stack's goals."""
        return self.guard.situation(self, self.belief, (f.plan.goal for f in self.stack))

    def after_cycle(self, cyc: Cycle) -> None:
        """A cycle closed: refine-flat and every mechanism hear of it (before the guard's livelock check)."""
        if self.strategy.refine_flat:
            self._flat_steps.on_cycle(self, cyc)
        for m in self.mechanisms:
            m.after_cycle(self, cyc)

    def commit(self, cyc: Cycle) -> str:  # the reconsidering mechanisms read :attr:`committed`
        return "committing to the current plans (no reconsideration until the belief is one not held before)"

    def end_commitment(self) -> str:
        return "commitment ends"

    def give_up(self, outcome: Outcome, reason: str) -> None:
        """A mechanism ends the run after this action with ``reason`` (checked by the guard's watch)."""
        self.guard.give_up(outcome, reason)

    def goal_holds(self) -> bool:
        return self.holds_goal(self.problem.goal)

    refinement_key = staticmethod(refinement_key)

    # -- the loop ------------------------------------------------------------------
    def run(self) -> Metrics:
        self._t0 = time.perf_counter()
        self._last_failure = ""
        self._last_status = None
        goal = self.problem.goal
        stages = tuple(PlanStep(None, g) for g in self.problem.stages)
        root_plan = Plan((PlanStep(None, TRUE), *stages, PlanStep(None, goal)), self.base_levels)
        self.push(root_plan, None, root=True)
        self.guard.start(self)
        outcome, reason = Outcome.REACHED, ""
        consecutive_failures = 0
        looks = 0  # fresh looks since the last plan (acting/reobserve.py)
        while self.stack:
            over = self.strategy.exhausted(self.metrics, time.perf_counter() - self._t0)
            if over is not None:
                outcome, reason = over
                break
            f = self.stack[-1]
            if not self.applicable(f):
                done = self.holds_goal(f.plan.goal)
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
                    # refinements floor the operators refined above them (acting/refine.py), so a chain
                    # is bounded by the criticality classes; a hierarchy with more is stopped here
                    outcome, reason = Outcome.LIMIT, (
                        f"plan stack deeper than {self.strategy.max_depth} (refining "
                        f"{action.pddl() if action is not None else 'a goal'} of plan {f.plan_id}); "
                        "raise Strategy.max_depth if the hierarchy has that many criticality classes")
                    break
                key = self.refinement_key(f)
                self._refinements[key] += 1
                if self._refinements[key] > self.strategy.max_refinements:
                    why = (
                        f"step {f.i if not f.root else 1} of plan {f.plan_id} (or of identical plans "
                        f"made for it) refined {self.strategy.max_refinements} times without an action "
                        "in between"
                    )
                    if self._flat_steps.fall_back(self, f, key, why, reset=True):
                        continue  # abstract plans that refine but never reach an action (not downward
                        # refinable: a held-out mine's battery and route in one class): plan concretely
                    if f.root:
                        if self._flat_steps.last_resort(self, f"no progress: {why}"):
                            continue
                        outcome, reason = Outcome.FAILED, f"no progress: {why}{flat_hint(self, key)}"
                        break
                    self.trace.emit("note", plan_id=f.plan_id, text=f"executive: gave up: {why}")
                    self.pop("failed")
                    continue
                levels = f.plan.levels if action is None else f.plan.levels.next_level(action)
                if f.root:
                    levels = self.base_levels
                if key in self._flat_steps:
                    levels = flat_levels()
                new = None  # a short refinement needs no planner call (a domain's own planner is asked)
                if action is not None and self.strategy.direct_refinements and not (
                        f.root or key in self._flat_steps or self.strategy.domain_planner):
                    new = self.direct_plan(step.goal, levels, action,
                                           f.plan.levels.floored([action]) is f.plan.levels)
                if new is None:
                    share = root_time_share(self, f, key, levels)
                    new = self.make_plan(step.goal, levels, f, time_share=share)
                    if new is not None and action is not None:
                        new = refine_without_swaps(self, new, step.goal, levels, f, action)
                if new is None:
                    consecutive_failures += 1
                    if self._flat_steps.fall_back(self, f, key, f"no abstract plan ({self._last_failure})"):
                        continue  # not even an abstract plan was found: plan the goal concretely
                    if f.root:
                        timed_out = self._last_status is PlanStatus.TIME_LIMIT
                        if not timed_out and look_again(self.belief, self.trace, looks, self._last_failure):
                            looks += 1
                            continue
                        # (an abstract level drops preconditions: with no first step learnt unrefinable,
                        # an abstract "unsolvable" is the concrete one's too, and a flat search would
                        # only prove it again at length)
                        if (not timed_out and len(self.nogoods) > 0 and not concrete(self.domain, levels)
                                and self._flat_steps.last_resort(
                                    self, f"no abstract plan for the goal once its first steps were found "
                                          f"unrefinable ({self._last_failure})")):
                            continue
                        outcome, reason = root_failure(self, levels, key, timed_out)
                        break
                    if consecutive_failures > 3 * self.strategy.max_depth:
                        if self._flat_steps.last_resort(self, f"repeated planning failures ({self._last_failure})"):
                            consecutive_failures = 0
                            continue
                        outcome, reason = Outcome.FAILED, f"repeated planning failures ({self._last_failure})"
                        break
                    # the refined step cannot be achieved from here: learn it and re-refine one
                    # level up; with refine-flat, a root left with no abstract plan, or plans that
                    # cycle (FlatSteps.check_cycle), plan the goal concretely
                    self.backtrack(f, action)
                    continue
                consecutive_failures = looks = 0
                self.push(new, f)
            else:
                self.execute(f, action)
                self.reconsider()
                if self.strategy.refine_flat:
                    self._flat_steps.check_cycle(self)
                stop = self.guard.watch(self, self.last_observation)  # a livelock's or a stall's end
                if stop is not None and stop[0] is Outcome.LIVELOCK and self._flat_steps.last_resort(self, stop[1]):
                    continue  # the abstract plans livelocked: the concrete ones start the guard's count again
                if stop is not None:
                    outcome, reason = stop
                    break
        if outcome is Outcome.REACHED and not self.goal_holds():
            outcome, reason = Outcome.FAILED, "plan stack emptied before the goal held"
        self.metrics.outcome = outcome
        self.metrics.reason = reason
        judge(self.domain, self.problem.goal, self.belief, self.world, self.metrics, self.trace)
        self.metrics.wall_s = time.perf_counter() - self._t0
        return self.metrics
