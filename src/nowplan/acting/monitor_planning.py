"""How the monitor plans its repairs: the planner calls and the three alternatives (seed 003).

:class:`MonitorPlanning` is the part of :class:`nowplan.acting.monitor.Monitor`
that makes plans: ``_plan`` (the domain's own planner, a stored plan, or the
regression planner within the run's remaining time), ``_plan_goal`` (flat,
or at the strategy's levels under HPN), and ``_make`` / ``_compose``, which
turn an alternative (goal, intermediate state, restore) into a
:class:`~nowplan.acting.monitor_repair.Repair`.  The monitor's state it reads
is declared below and set by ``Monitor.__init__``.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

from nowplan.acting.monitor_escalation import Escalation
from nowplan.acting.monitor_repair import Alternative, Candidate, MonitorConfig, MonitorStats, Repair
from nowplan.acting.monitor_support import (
    MonitorSupport,
    drop_loops,
    plan_from_actions,
    simulate,
    target_goal,
)
from nowplan.acting.plan_library import StoredPlan, state_key
from nowplan.core.atoms import Goal, entails
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.state import State
from nowplan.planning.derived_state import derived_closure
from nowplan.planning.plan import PlanResult, PlanStatus
from nowplan.planning.regression import PlannerConfig
from nowplan.planning.regression import plan as regression_plan
from nowplan.planning.task import forward_unsupported

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame


class MonitorPlanning:
    """The monitor's planning and repair making (a base class of :class:`~nowplan.acting.monitor.Monitor`)."""

    # set by Monitor.__init__
    config: MonitorConfig
    stats: MonitorStats
    support: MonitorSupport
    escalation: Escalation
    plans: list[StoredPlan]
    _flat_goal: bool

    def _own_planner(self) -> Any:
        if self.config.planner == "domain" and self.support.planner is not None:
            return self.support.planner
        return None

    def _plan(
        self, ex: Executive, state: State, goal: Goal, levels: LevelMap | None = None, *, bounded: bool = True,
    ) -> PlanResult:
        """Plan ``goal`` from ``state`` (flat unless ``levels``) within the run's remaining time.

        ``bounded``: a flat call gets the planner's shortcut budget (``shortcut_nodes``) instead of
        its full one: a repair that needs a bigger search is no small repair, and the monitor has
        other alternatives (and HPN its own replanning) to fall back on.
        """
        levels = levels or flat_levels()
        # after an escalation a stored plan from this state may be a restore's, the very detour
        # the world keeps undoing: plan afresh
        if self.config.reuse and not self.escalation.escalated and entails(goal, ex.problem.goal, ex.domain.rules) \
                and entails(ex.problem.goal, goal, ex.domain.rules):
            reused = self._reuse(ex, state, goal)
            if reused is not None:
                return reused
        own = self._own_planner()
        if own is not None:
            res: PlanResult = own(ex.domain, ex.problem.objects, state, goal, ex.rng)
        else:
            res = regression_plan(ex.domain, ex.problem.objects, state, goal, levels,
                                  self._config(ex, bounded), ex.context(), ex.rng)
        ex.metrics.planning_cpu_s += res.cpu_time_s
        self.stats.planning_s += res.cpu_time_s
        if res.solved:
            ex.metrics.plans_made += 1
        else:
            ex.metrics.plan_failures += 1
        return res

    @staticmethod
    def _config(ex: Executive, bounded: bool) -> PlannerConfig:
        cfg = ex.strategy.planner
        changes: dict[str, Any] = {}
        remaining = max(ex.remaining_time(), 0.01)
        if remaining < cfg.time_limit:
            changes["time_limit"] = remaining
        if bounded and cfg.shortcut_nodes < cfg.max_nodes:
            changes["max_nodes"] = cfg.shortcut_nodes
        return replace(cfg, **changes) if changes else cfg

    def _plan_goal(self, ex: Executive, state: State) -> PlanResult:
        """A plan from ``state`` to the task's goal: flat, or at the strategy's levels.

        The seed plans flat (its planner has no hierarchy) and its flat plans feed the library's
        intermediate states.  Under HPN the monitor plans the goal flat only where the flat plan
        is searched forward (the belief lists its facts, no generators or tests: logistics,
        a few milliseconds); elsewhere a flat plan for the whole goal is what HPN exists to
        avoid (marsupial: 50,000 regression expansions without a plan, 30-60 s per call,
        where HPN's abstract plan takes 31), so the goal is planned at the strategy's levels,
        as the executive plans its root, and HPN refines the abstract plan.  A flat search
        that runs out of its budget also turns the monitor to the hierarchy for the rest of the run.
        """
        goal, hier = ex.problem.goal, ex.strategy.hierarchical
        if hier and self._flat_goal and self._own_planner() is None:
            why = None if ex.strategy.planner.engine != "regression" else "the planner is set to regress"
            why = why or forward_unsupported(ex.domain, state)
            if why is not None:
                self._to_hierarchy(ex, f"a flat plan to the goal would be searched by regression ({why})")
        if self._flat_goal or not hier:
            res = self._plan(ex, state, goal, bounded=False)
            if res.solved or not hier or res.status not in (PlanStatus.NODE_LIMIT, PlanStatus.TIME_LIMIT):
                return res
            self._to_hierarchy(ex, f"flat planning to the goal: {res.status.value}: {res.reason}")
        return self._plan(ex, state, goal, ex.base_levels, bounded=False)

    def _to_hierarchy(self, ex: Executive, why: str) -> None:
        self._flat_goal = False
        self.stats.hierarchical_goal = why
        ex.trace.emit("note", text=f"monitor: {why}; planning the goal at the strategy's levels from now on")

    def _reuse(self, ex: Executive, state: State, goal: Goal) -> PlanResult | None:
        key = state_key(state)
        for sp in sorted((p for p in self.plans if p.init_key == key), key=lambda p: p.cost):
            plan = plan_from_actions(ex.domain, sp.rebuild(ex.domain), goal)
            if plan is not None and simulate(ex.domain, state, plan.actions,
                                             derived_closure(ex.domain, ex.problem.objects)) is not None:
                self.stats.reuses += 1
                return PlanResult(PlanStatus.SOLVED, plan, "", method="library")
        return None

    def _make(
        self, alt: Alternative, ex: Executive, f: Frame, expected: State, observed: State,
        cand: Candidate | None,
    ) -> Repair | None:
        dom, goal = ex.domain, ex.problem.goal
        if alt is Alternative.GOAL:
            res = self._plan_goal(ex, observed)
            if not res.solved or res.plan is None:
                return None
            flat = all(res.plan.is_primitive(i) for i in range(1, len(res.plan) + 1))
            return Repair(alt, res.plan, "replace_all", res.plan.cost(), 0.0, res.cpu_time_s,
                          f"plan from the observed model to the goal ({res.method}"
                          f"{'' if flat else ', abstract: HPN refines it'})")
        if alt is Alternative.INTERMEDIATE:
            if cand is None:
                return None
            suffix = cand.plan.rebuild(dom)[cand.index:]
            tail = plan_from_actions(dom, suffix, goal)
            if tail is None:
                return None
            return self._compose(ex, alt, observed, tail.preimage(0).atoms, suffix, goal, "replace_all",
                                 f"go to state {cand.index} of stored plan {cand.plan.id}, then its plan")
        # RESTORE
        primitive = all(f.plan.is_primitive(i) for i in range(f.i + 1, f.n + 1))
        atoms = f.plan.preimage(f.i).atoms if self.config.restore_target == "preimage" \
            else frozenset(expected.atoms())
        if primitive:
            rep = self._compose(ex, alt, observed, atoms, list(f.plan.actions[f.i:]), f.plan.goal,
                                "replace_frame", "plan back to the expected model, then continue")
            if rep is not None:
                return rep
        target = target_goal(list(atoms), frozenset(), dom)
        if target is None:
            return None
        res = self._plan(ex, observed, target)
        if not res.solved or res.plan is None:
            return None
        rest = sum(a.cost() for a in f.plan.actions[f.i:])
        return Repair(alt, res.plan, "on_top", res.plan.cost(), rest, res.cpu_time_s,
                      "plan back to the expected model, then continue", target)

    def _compose(
        self, ex: Executive, alt: Alternative, observed: State, target_atoms: Any, tail: list[Any],
        goal: Goal, mode: str, detail: str,
    ) -> Repair | None:
        """Repair to ``target_atoms`` (minus the agent's own body), then ``tail``, as one plan."""
        dom = ex.domain
        ignore = self.support.ignore if self.support.adapt is not None else frozenset()
        target = target_goal(list(target_atoms), ignore, dom)
        if target is None:
            return None
        res = self._plan(ex, observed, target)
        if not res.solved or res.plan is None:
            return None
        actions = list(res.plan.actions) + list(tail)
        if self.support.adapt is not None:
            actions = self.support.adapt(actions, observed)
        states = simulate(dom, observed, actions, derived_closure(dom, ex.problem.objects))
        if states is None:
            return None
        plan = plan_from_actions(dom, actions, goal)
        shorter = drop_loops(states, actions)
        if len(shorter) < len(actions):
            cut = plan_from_actions(dom, shorter, goal)
            if cut is not None:
                self.stats.loops_dropped += len(actions) - len(shorter)
                plan = cut
        if plan is None:
            return None
        repair_cost = plan.cost() - sum(a.cost() for a in tail)
        return Repair(alt, plan, mode, max(repair_cost, 0.0), sum(a.cost() for a in tail),
                      res.cpu_time_s, detail, target)
