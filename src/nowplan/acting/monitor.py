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
the planner calls and the repairs they make are in
:mod:`nowplan.acting.monitor_planning` (a base class of :class:`Monitor`);
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
from nowplan.acting.monitor_support import MonitorSupport, simulate, state_of, support_for
from nowplan.acting.monitor_escalation import Escalation
from nowplan.acting.monitor_planning import MonitorPlanning
from nowplan.acting.plan_library import PlanLibrary, Rank, StoredPlan, goal_key, state_index, state_key
from nowplan.belief.protocols import Reobserves
from nowplan.core.atoms import entails
from nowplan.core.domain import Domain
from nowplan.core.state import State
from nowplan.errors import ModelError, ScenarioError
from nowplan.planning.derived_state import derived_closure
from nowplan.planning.plan import Plan

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


def _tests_not_on_states(ex: Executive) -> list[str]:
    """The tested predicates whose test cannot answer on a :class:`State` (it reads something only the
    belief has, e.g. a particle belief's odds: an AttributeError or TypeError): tried once on the belief's
    state, with the first objects of the argument types.  A test that reads the state's facts
    (marsupial's ``same_city``) works; one that fails on those particular arguments (a KeyError, say)
    is not taken for a test that needs the belief."""
    state = state_of(ex.belief)
    objects = list(ex.problem.objects.items())
    out: list[str] = []
    for p in ex.domain.predicates.values():
        if p.test is None:
            continue
        args = tuple(next((o for o, t in objects if t == want), objects[0][0] if objects else None)
                     for want in (p.arg_types or (None,) * p.arity)[:p.arity])
        try:
            p.test(state, args, True)
        except (AttributeError, TypeError):  # it reads what a State has not (a particle belief's odds)
            out.append(p.name)
        except Exception:  # noqa: BLE001 - another error is about these arguments, not about States
            continue
    return sorted(out)


class Monitor(MonitorPlanning, Mechanism):
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
        closure = derived_closure(ex.domain, ex.problem.objects)  # (derived predicates: recomputed)
        if closure is not None:
            expected = closure(expected)
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
    def check(self, ex: Executive) -> None:
        """Refused before the run: a belief that is not a point state, or predicates tested on the belief."""
        try:
            state_of(ex.belief)
        except ModelError as err:
            raise ScenarioError(
                "the monitor strategies compare an expected and an observed symbolic world model "
                f"(seed 003), but domain {ex.domain.name}'s belief is a {type(ex.belief).__name__}, "
                "not a point state; drop the monitor switch from the strategy"
            ) from err
        tested = _tests_not_on_states(ex)
        if tested:
            raise ScenarioError(
                "the monitor strategies plan over symbolic world models (States), but domain "
                f"{ex.domain.name}'s predicate(s) {', '.join(tested)} are tested on the belief "
                "(Predicate(test=...)), which a State cannot answer; drop the monitor switch from the strategy"
            )

    def _setup(self, ex: Executive) -> None:
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

    def _store(self, ex: Executive, plan: Plan) -> None:
        goal = ex.problem.goal
        if not entails(plan.goal, goal, ex.domain.rules):
            return  # a repair toward an intermediate target, not toward the task's goal
        if not all(plan.is_primitive(i) for i in range(1, len(plan) + 1)):
            return  # only primitive plans have intermediate states to store
        init = state_of(ex.belief)
        actions = list(plan.actions)
        states = simulate(ex.domain, init, actions, derived_closure(ex.domain, ex.problem.objects))
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

    # -- planning (the calls and the repairs: nowplan.acting.monitor_planning) ----------------
    def _initial_plan(self, ex: Executive, root: Frame) -> None:
        state = state_of(ex.belief)
        if ex.domain.satisfies(state, ex.problem.goal):
            return
        res = self._plan(ex, state, ex.problem.goal)
        if res.solved and res.plan is not None:
            self._push(ex, root, res.plan, res.method, res.cpu_time_s)

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
