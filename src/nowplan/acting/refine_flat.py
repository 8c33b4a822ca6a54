"""refine-flat: plan a goal concretely when its abstract plans cannot be refined or cycle.

An ordered-monotonic hierarchy (an automatic one, say) need not be downward
refinable: an abstract plan may have no refinement, or refinements that succeed
may undo each other so that the concrete state cycles.  The executive keeps a
:class:`FlatSteps` record: the steps (by :func:`refinement_key`) whose goal is
planned at the flat level from then on, and the symbolic states seen after
actions since the last news (a failed action or an exogenous change).

Two ways in.  The ``refine-flat`` switch is eager: the root's first failure to
refine, its first clean cycle or a state reached :data:`CYCLE_VISITS` times plans
the goal concretely.  Every hierarchical strategy also has the *last resort*
(:meth:`FlatSteps.last_resort`, off with the ``nofallback`` switch): where the run
would end because the root's abstract plans make no progress ("no progress", no
abstract plan, repeated planning failures, a livelock), the root goal is planned
concretely once instead, and the run says so (``Metrics.flat_fallbacks``).  A run
that reaches its goal hierarchically never meets it, so the seeds' HPN is
unchanged where its hierarchy is downward refinable.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Hashable
from dataclasses import replace
from typing import TYPE_CHECKING

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.levels import LevelMap
from nowplan.planning.config import PlannerConfig
from nowplan.planning.regression import concrete

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame
    from nowplan.acting.progress import Cycle

CYCLE_VISITS = 3  # visits of one symbolic state that count as a cycle
# backtracks from one abstract step (its action, the plan's goal and levels) over the run with no more
# root goal atoms holding than before, that count as abstract plans making no progress (the last resort)
REPEATED_BACKTRACKS = 8
# the part of the run's remaining time the root's abstract plan may take under refine-flat: the rest
# is left to the concrete plan made when no abstract one is found (with `nowplan plan`'s node budget a
# hard top level, IPC floor-tile's is nearly the whole problem, can search until the run's time is out)
ROOT_ABSTRACT_SHARE = 0.5


def root_time_share(ex: Executive, f: Frame, key: Hashable, levels: LevelMap) -> float:
    """``ROOT_ABSTRACT_SHARE`` for the root's first, abstract plan under refine-flat, else 1."""
    if not (f.root and ex.strategy.refine_flat and key not in ex._flat_steps):
        return 1.0
    return 1.0 if concrete(ex.domain, levels) else ROOT_ABSTRACT_SHARE


def flat_hint(ex: Executive, key: Hashable) -> str:
    """What to try when the root gives up on its abstract plans with refine-flat off: "" with it on or
    where the goal was planned concretely already (then the hierarchy is not the cause)."""
    if ex.strategy.refine_flat or key in ex._flat_steps:
        return ""
    hint = "; the criticalities may not be downward refinable (abstract plans that no refinement reaches)"
    if "flat" in ex.domain.unsupported:
        return hint  # (no switch plans such a domain's goal concretely)
    if not ex.strategy.last_resort:
        return (hint + ": without the switch nofallback the executive plans such a goal concretely as a "
                "last resort, and with refine-flat (hpn+refine-flat) as soon as its abstract plans fail")
    return hint + ": the switch refine-flat (hpn+refine-flat) plans such a goal concretely"


def may_fall_back(ex: Executive) -> bool:
    """The strategy has the last resort, plans at several levels, and the domain can be planned flat
    (``Domain.unsupported["flat"]``: marsupial's loader is planned in the now)."""
    return ex.strategy.last_resort and not ex.single_level and "flat" not in ex.domain.unsupported


def call_config(cfg: PlannerConfig, root: bool) -> PlannerConfig:
    """A planner call's settings: below the root (a refinement), a forward search keeps the
    regression search's node budget ``max_nodes`` even where the strategy gives forward searches a
    larger one (a PDDL run gets ``nowplan plan``'s, which the time limit ends): a refinement that
    cannot be made is given up as soon as before, and the executive backtracks, while the root's
    plans, the whole goal's, get the budget ``nowplan plan`` would."""
    if not root and cfg.forward_max_nodes is not None and cfg.forward_max_nodes > cfg.max_nodes:
        cfg = replace(cfg, forward_max_nodes=cfg.max_nodes)
    return cfg


def refinement_key(f: Frame) -> Hashable:
    """What the loop guard counts refinements of: a step of a plan *by content*.

    A plan that fails is often replanned into the very same plan (the belief has not
    changed); counting per plan id would give every copy a fresh allowance, and the
    allowances multiply down the levels of the stack.  Counting per content bounds the
    refinements of one step of one plan, however often it is remade, until the next action.
    """
    if f.root:
        return ("root", f.i)
    acts = tuple(s.action.key if s.action is not None else None for s in f.plan.steps)
    return (acts, f.plan.goal, f.i)


class FlatSteps:
    """The steps planned concretely, and the states visited since the last news."""

    def __init__(self) -> None:
        self.steps: set[Hashable] = set()
        self.visits: Counter[Hashable] = Counter()
        self.backtracks: Counter[Hashable] = Counter()  # since the root goal last came closer
        self._best = -1  # the most root goal atoms seen holding

    def __contains__(self, key: Hashable) -> bool:
        return key in self.steps

    def add(self, key: Hashable) -> None:
        self.steps.add(key)

    def fall_back(self, ex: Executive, f: Frame, key: Hashable, why: str, reset: bool = False) -> bool:
        """Under refine-flat, plan the root step ``key`` concretely from now on (``why``: its abstract
        plans found none, or refined without an action); ``False`` where refine-flat is off, ``f`` is
        no root or the step is planned concretely already (then the executive gives up as without).
        ``reset``: the step's refinement count starts again (its allowance was spent on abstract plans)."""
        if not (f.root and ex.strategy.refine_flat) or key in self.steps:
            return False
        self.steps.add(key)
        if reset:
            ex._refinements[key] = 0
        ex.trace.emit("note", plan_id=f.plan_id,
                      text=f"executive: refine-flat: {why}; planning the goal concretely")
        return True

    def check_cycle(self, ex: Executive) -> None:
        """A symbolic state reached a third time means the hierarchical plans cycle
        (refinements that succeed but undo each other): plan the current root goal concretely."""
        if not isinstance(ex.belief, SymbolicBelief) or not ex.stack or not ex.stack[0].root:
            return
        obs = ex.last_observation
        if not obs.success or obs.exogenous:
            # a failed action or the world's own change is news: states seen before it were
            # left for a reason the plans did not know, so revisiting them is no cycle
            self.visits.clear()
            return
        # the belief's state itself (hashed and compared by its fluents, no sorted atom list made)
        state = ex.belief.state
        self.visits[state] += 1
        if self.visits[state] >= CYCLE_VISITS:
            self._flatten_root(ex, f"state reached {CYCLE_VISITS} times: the hierarchical plans cycle")

    def on_cycle(self, ex: Executive, cyc: Cycle) -> None:
        """The progress guard saw the belief and the plan stack's goals repeat with no failure and no
        exogenous change in between (any belief with a fingerprint, a particle belief too, where
        :meth:`check_cycle` sees symbolic states only): the hierarchical plans undo each other, so plan
        the root goal concretely (once; later cycles go on to the guard's livelock bound)."""
        if cyc.clean and ex.stack and ex.stack[0].root:
            self._flatten_root(ex, f"the guard's cycle ({cyc.describe()}): the hierarchical plans cycle")

    def last_resort(self, ex: Executive, why: str) -> bool:
        """The run would end for ``why`` (the root's abstract plans make no progress): plan the current
        root step's goal concretely instead, once per root step; ``False`` where the strategy has no
        last resort, plans at one level only or cannot be planned flat (:func:`may_fall_back`), or that
        step is planned concretely already (then the run ends as it would have)."""
        if not may_fall_back(ex) or not ex.stack or not ex.stack[0].root:
            return False
        if not self._flatten_root(ex, f"last resort: {why}", "give up"):
            return False
        ex._refinements[refinement_key(ex.stack[0])] = 0  # the concrete plans' own allowance
        ex.guard.forgive()  # and the guard's count of cycles and repeated actions starts again
        ex.metrics.flat_fallbacks += 1
        return True

    def after_backtrack(self, ex: Executive, key: Hashable, step: str) -> bool:
        """A step (``key``: its action, its plan's goal and levels; ``step`` its text) could not be
        refined.  The same step backtracked :data:`REPEATED_BACKTRACKS` times with no root goal atom
        gained meanwhile means the abstract plans keep proposing what no refinement reaches, in rounds
        of actions that the guard may not see as cycles (each failure or change of the world's ends
        one): the last resort.  ``True`` where it was taken (the stack is back at the root)."""
        if not may_fall_back(ex):
            return False
        achieved = ex.domain.count_holding(ex.truth, ex.problem.goal.atoms)
        if achieved > self._best:
            self._best = achieved
            self.backtracks.clear()
        self.backtracks[key] += 1
        n = self.backtracks[key]
        if n < REPEATED_BACKTRACKS:
            return False
        return self.last_resort(ex, f"{step} could not be refined {n} times with no goal atom gained "
                                    "(the abstract plans keep proposing it)")

    def _flatten_root(self, ex: Executive, why: str, popped: str = "cycle") -> bool:
        """Plan the root step's goal concretely from now on (``False``: it is already)."""
        root = ex.stack[0]
        key = refinement_key(root)
        if key in self.steps:
            return False
        self.steps.add(key)
        ex.trace.emit("note", plan_id=root.plan_id,
                      text=f"executive: refine-flat: {why}; planning the goal concretely")
        while len(ex.stack) > 1:
            ex.pop(popped)
        self.visits.clear()
        return True
