"""The expected-vs-observed monitor with a plan library (seed 003), as strategy switches.

Seed 003's task scheduler executes a step, updates the *expected* world
model, observes, and hands both models to ``Replanner()``, which picks one
of three alternatives (:mod:`nowplan.acting.monitor_repair`).  Here that
loop is a :class:`~nowplan.acting.mechanisms.Mechanism` of the plan-stack
executive: ``next_step`` remembers the model before a step, ``after_action``
compares expected and observed models with the domain's distance
(:mod:`nowplan.acting.monitor_support`) and rewrites the plan stack, and
``after_push`` stores every primitive plan toward the task's goal in the
plan library (:mod:`nowplan.acting.plan_library`) with its intermediate
states.  When the domain registers its own planner (the seed's means-ends
planner for shuffled pieces) the monitor makes every plan with it;
otherwise it uses the regression planner, flat.  When no alternative can
be planned and the belief offers ``reobserve()`` (a fresh look), the monitor
calls it (up to three times) and tries again, since an impossible model is often a
misperceived one.  Under HPN the goal is planned at the strategy's levels
where a flat plan would be a regression search (:meth:`Monitor._plan_goal`);
when restoring loops the monitor escalates to replanning to the goal
(:mod:`nowplan.acting.monitor_escalation`).

Switches: ``monitor`` (the seed's rule), ``monitor-goal`` (always replan to
the goal), ``monitor-restore`` (always restore), ``monitor-cost`` (cheapest
alternative), ``monitor-rule-cost`` (the cheapest of the alternatives the
seed's thresholds admit).  Thresholds, library and accounting come from
:func:`monitor_settings` (default: :class:`MonitorConfig` with the library
file named by ``NOWPLAN_PLAN_LIBRARY``, if set).
"""

from __future__ import annotations

import contextlib
import logging
import os
from collections.abc import Iterator
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from nowplan.acting.mechanisms import Mechanism, Switch, register_switch
from nowplan.acting.monitor_repair import (
    Alternative,
    Candidate,
    MonitorConfig,
    MonitorStats,
    Repair,
    order_to_try,
)
from nowplan.acting.monitor_support import (
    MonitorSupport,
    drop_loops,
    plan_from_actions,
    simulate,
    state_of,
    support_for,
    target_goal,
)
from nowplan.acting.monitor_escalation import Escalation
from nowplan.acting.plan_library import PlanLibrary, Rank, StoredPlan, goal_key, state_index, state_key
from nowplan.belief.protocols import Reobserves
from nowplan.core.atoms import Goal, entails
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.state import State
from nowplan.errors import ModelError, ScenarioError
from nowplan.planning.plan import Plan, PlanResult, PlanStatus
from nowplan.planning.regression import PlannerConfig
from nowplan.planning.regression import plan as regression_plan
from nowplan.planning.task import forward_unsupported

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame
    from nowplan.acting.progress import Cycle
    from nowplan.planning.plan import PlanStep

__all__ = ["Monitor", "MonitorConfig", "default_config", "monitor_settings"]

log = logging.getLogger(__name__)

_ACTIVE: MonitorConfig | None = None
REOBSERVATIONS = 3  # fresh looks when nothing can be planned from the observed model (each is a new sample)


def default_config() -> MonitorConfig:
    if _ACTIVE is not None:
        return _ACTIVE
    return MonitorConfig(library_path=os.environ.get("NOWPLAN_PLAN_LIBRARY") or None)


@contextlib.contextmanager
def monitor_settings(config: MonitorConfig) -> Iterator[MonitorConfig]:
    """Use ``config`` for monitors created inside the block (strategies are parsed by name)."""
    global _ACTIVE
    old, _ACTIVE = _ACTIVE, config
    try:
        yield config
    finally:
        _ACTIVE = old


class Monitor(Mechanism):
    name = "monitor"

    def __init__(self, config: MonitorConfig) -> None:
        self.config = config
        self.stats = MonitorStats()
        self.support = MonitorSupport()
        self.library: PlanLibrary | None = None
        self.plans: list[StoredPlan] = []  # every plan toward this run's goal, stored or found
        self.current: StoredPlan | None = None  # the plan being executed (the seed's current path)
        self._prev: State | None = None
        self._goal_key = ""
        self._next_mem_id = -1
        self._index: dict[State, tuple[Rank, StoredPlan, int]] = {}
        self._indexed = 0  # how many of self.plans are in self._index
        # escalation: restore / intermediate targets chosen, and those the agent's own actions reached
        self.escalation = Escalation()
        self._flat_goal = True  # plan the goal flat (False once that exceeded its budget; see _plan_goal)
        self._repairs: set[int] = set()  # plan ids of the restore / intermediate plans pushed

    # -- hooks ---------------------------------------------------------------------
    def after_push(self, ex: Executive, frame: Frame) -> None:
        if frame.root:
            self._setup(ex)
            if self._own_planner() is not None:
                self._initial_plan(ex, frame)
            return
        self._store(ex, frame.plan)

    def next_step(self, ex: Executive, frame: Frame) -> PlanStep | None:
        self._prev = state_of(ex.belief)
        return None

    def after_action(self, ex: Executive) -> None:
        prev, self._prev = self._prev, None
        if prev is None or len(ex.stack) < 2:
            return
        if ex.committed:
            return  # after a cycle: the executive's own failure handling, no stack rewrites
        f = ex.stack[-1]
        action = f.plan.steps[f.i].action if 0 < f.i <= f.n else None
        if f.root or action is None:
            return
        expected = prev.apply(action.effects())
        self.escalation.note(ex.domain, expected)
        observed = state_of(ex.belief)
        dm = float(self.support.distance(expected, observed))
        if dm == 0:
            return
        if self.escalation.goal_undone(ex, expected):
            return
        self.stats.surprises += 1
        self.stats.distances.append(dm)
        if ex.goal_holds():
            ex.trace.emit("note", text=f"monitor: surprise (dm={dm:g}) but the goal holds")
            return
        order, repairs, dm1 = self._alternatives(ex, f, expected, observed, dm)
        looks = 0
        while not repairs and isinstance(ex.belief, Reobserves) and looks < REOBSERVATIONS:
            # nothing can be planned from this model: perhaps it is misperceived; look again
            ex.trace.emit("note", text=f"monitor: no alternative could be planned (dm={dm:g}); observing again")
            self.stats.reobservations += 1
            looks += 1
            ex.belief.reobserve()
            observed = state_of(ex.belief)
            dm = float(self.support.distance(expected, observed))
            if dm == 0:
                return
            order, repairs, dm1 = self._alternatives(ex, f, expected, observed, dm)
        if not repairs:
            self.stats.unresolved += 1
            ex.trace.emit("note", text=f"monitor: no alternative could be planned (dm={dm:g}); "
                          "the executive replans")
            return
        chosen = min(repairs, key=lambda r: r.total(self.config)) if self.config.compares \
            else repairs[0]
        if chosen.alternative is not order[0] and not self.config.compares:
            self.stats.fallbacks += 1
        if self.config.escalate and self.escalation.undone(chosen.target):
            # the agent's own actions had reached this model and the world took it away again:
            # restoring once more chases the world (seed 003: go directly to the final state)
            self._escalate(ex, f"the world undid a {chosen.alternative.value} the agent had completed "
                           f"(the model it went back to, {len(chosen.target or ())} atom(s), was reached and lost)")
            to_goal = next((r for r in repairs if r.alternative is Alternative.GOAL), None) \
                or self._make(Alternative.GOAL, ex, f, expected, observed, None)
            chosen = to_goal or chosen
        self.escalation.chose(chosen.target)
        self._apply(ex, f, chosen, dm, dm1)

    def after_cycle(self, ex: Executive, cycle: Cycle) -> None:
        """The progress guard found a cycle: stop restoring, replan to the goal (seed 003's third way).

        Restoring the expected model, or re-entering a stored plan, is what the monitor adds to
        HPN; when the agent comes back to a situation it had left, those repairs are (or may be)
        the loop, and committing to them would repeat it.  The monitor escalates to replanning
        to the goal for the rest of the run, and replaces its repair plans on the stack now.
        """
        if self.config.decision == "goal" or not self.config.escalate or self.escalation.escalated:
            return
        self._escalate(ex, f"the progress guard found a cycle: {cycle.describe()}")
        if not any(fr.plan_id in self._repairs for fr in ex.stack) or ex.goal_holds():
            return
        observed = state_of(ex.belief)
        rep = self._make(Alternative.GOAL, ex, ex.stack[-1], observed, observed, None)
        if rep is not None:
            self._apply(ex, ex.stack[-1], rep, 0.0, None)

    def _escalate(self, ex: Executive, why: str) -> None:
        self.stats.escalated = why
        self.escalation.escalate(ex, self.config.decision, why)

    def _alternatives(
        self, ex: Executive, f: Frame, expected: State, observed: State, dm: float,
    ) -> tuple[list[Alternative], list[Repair], float | None]:
        """The alternatives to try, the repairs that could be planned (one, or all when comparing), dm1."""
        escalated = self.escalation.escalated
        cand = self._closest(observed, ex.domain) if self.config.uses_library and not escalated else None
        dm1 = cand.distance if cand is not None else None
        order = [Alternative.GOAL] if escalated else order_to_try(self.config, dm, dm1)
        repairs: list[Repair] = []
        for alt in order:
            rep = self._make(alt, ex, f, expected, observed, cand)
            if rep is not None:
                repairs.append(rep)
                if not self.config.compares:
                    break
        return order, repairs, dm1

    # -- set-up and the library ----------------------------------------------------------
    def _setup(self, ex: Executive) -> None:
        try:
            state_of(ex.belief)
        except ModelError as err:
            raise ScenarioError(
                "the monitor strategies compare an expected and an observed symbolic world model "
                f"(seed 003), but domain {ex.domain.name}'s belief is a {type(ex.belief).__name__}, "
                "not a point state; drop the monitor switch from the strategy"
            ) from err
        self.support = support_for(ex.domain)
        self._goal_key = goal_key(ex.problem.goal)
        if self.config.library_path is not None:
            self.library = PlanLibrary(self.config.library_path)
            self.plans = self.library.toward(ex.domain.name, ex.problem.goal)
        else:
            self.library = None
            self.plans = []
        self._index, self._indexed = {}, 0
        log.info("monitor: %d stored plan(s) toward this goal", len(self.plans))

    def _own_planner(self) -> Any:
        if self.config.planner == "domain" and self.support.planner is not None:
            return self.support.planner
        return None

    def _store(self, ex: Executive, plan: Plan) -> None:
        goal = ex.problem.goal
        if not entails(plan.goal, goal, ex.domain.rules):
            return  # a repair toward an intermediate target, not toward the task's goal
        if not all(plan.is_primitive(i) for i in range(1, len(plan) + 1)):
            return  # only primitive plans have intermediate states to store
        init = state_of(ex.belief)
        actions = list(plan.actions)
        states = simulate(ex.domain, init, actions)
        if states is None:
            return
        if self.library is not None and self.config.library_write:
            pid = self.library.add(ex.domain.name, init, goal, actions, states)
        else:
            pid, self._next_mem_id = self._next_mem_id, self._next_mem_id - 1
        found = next((p for p in self.plans if p.id == pid), None)
        if found is None:
            found = StoredPlan(pid, ex.domain.name, state_key(init), self._goal_key,
                               tuple((a.name, a.args) for a in actions), tuple(states),
                               sum(a.cost() for a in actions))
            self.plans.append(found)
            self.stats.stored += 1
        self.current = found

    def _closest(self, observed: State, domain: Domain) -> Candidate | None:
        if self.config.library_scope == "path":
            pool = [self.current] if self.current is not None else []
            index = state_index(pool, domain)
        else:
            index = self._library_index(domain)
        best: tuple[float, float, float, int] | None = None
        out: Candidate | None = None
        for s, (rank, sp, j) in index.items():
            d = float(self.support.distance(s, observed))
            key = (d, *rank)
            if best is None or key < best:
                best, out = key, Candidate(sp, j, d)
        return out

    def _library_index(self, domain: Domain) -> dict[State, tuple[Rank, StoredPlan, int]]:
        """Each distinct state of the stored plans once, with its preferred occurrence.

        Replanning after every surprise stores a plan each time, and most of their states are
        shared; measuring the distance once per distinct state instead of once per occurrence
        keeps the closest-state search linear in what the library knows, not in its history.
        """
        if self._indexed < len(self.plans):
            state_index(self.plans[self._indexed:], domain, self._index)
            self._indexed = len(self.plans)
        return self._index

    # -- planning ----------------------------------------------------------------------
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
            if plan is not None and simulate(ex.domain, state, plan.actions) is not None:
                self.stats.reuses += 1
                return PlanResult(PlanStatus.SOLVED, plan, "", method="library")
        return None

    def _initial_plan(self, ex: Executive, root: Frame) -> None:
        state = state_of(ex.belief)
        if ex.domain.satisfies(state, ex.problem.goal):
            return
        res = self._plan(ex, state, ex.problem.goal)
        if res.solved and res.plan is not None:
            self._push(ex, root, res.plan, res.method, res.cpu_time_s)

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
        states = simulate(dom, observed, actions)
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

    # -- the plan stack ------------------------------------------------------------------
    def _apply(self, ex: Executive, f: Frame, rep: Repair, dm: float, dm1: float | None) -> None:
        alt = rep.alternative.value
        self.stats.decisions[alt] += 1
        self.stats.estimated_cost += rep.total(self.config)
        ex.metrics.replans += 1
        why = (f"{alt}: {rep.detail}; dm={dm:g}" + (f", dm1={dm1:g}" if dm1 is not None else "")
               + f", thr={self.config.thr:g}")
        ex.trace.emit("replan", plan_id=f.plan_id, trigger="monitor", reason=why)
        ex.trace.emit(
            "note", text=f"monitor chose {alt}", alternative=alt, dm=dm, dm1=dm1,
            repair_cost=round(rep.repair_cost, 6), continuation_cost=round(rep.continuation_cost, 6),
            planning_s=round(rep.planning_s, 6), decision=self.config.decision,
        )
        if rep.mode == "replace_all":
            while len(ex.stack) > 1:
                ex.pop("replaced")
        elif rep.mode == "replace_frame":
            ex.pop("replaced")
        fr = self._push(ex, ex.stack[-1], rep.plan, alt, rep.planning_s)
        if rep.alternative is not Alternative.GOAL:
            self._repairs.add(fr.plan_id)

    def _push(self, ex: Executive, parent: Frame, plan: Plan, method: str, cpu_s: float) -> Frame:
        """Push a plan the monitor made; the executive traces it like its own (a ``plan`` event)."""
        made = getattr(ex, "_made", None)
        if isinstance(made, dict):
            made[id(plan)] = {"method": method, "cpu_s": round(cpu_s, 6), "expanded": 0}
        return ex.push(plan, parent)


def _factory(decision: str | None) -> Any:
    def make(strategy: Any) -> Monitor:
        cfg = default_config()
        return Monitor(cfg if decision is None else replace(cfg, decision=decision))

    return make


register_switch(Switch("monitor", "expected-vs-observed monitor with a plan library, the seed's "
                       "decision rule (seed 003)", mechanism=_factory(None)))
register_switch(Switch("monitor-goal", "monitor that always replans to the goal after a surprise",
                       mechanism=_factory("goal")))
register_switch(Switch("monitor-restore", "monitor that always plans back to the expected model",
                       mechanism=_factory("restore")))
register_switch(Switch("monitor-cost", "monitor that plans every alternative and takes the cheapest",
                       mechanism=_factory("cost")))
register_switch(Switch("monitor-rule-cost", "monitor that plans the alternatives the seed's thresholds "
                       "admit (the goal always) and takes the cheapest", mechanism=_factory("rule-cost")))
