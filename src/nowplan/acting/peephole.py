"""RCHPN: dynamic peephole optimization of abstract plans (seed 002 Alg. 2–4).

Before each step of a plan is taken, the tail of the plan is looked at "in
the now", with the current belief:

* ``SelectGap`` (Alg. 3) starts at the highest pre-image ``g_i`` the belief
  satisfies (the highest true kernel) and moves later steps in front of the
  next one while :func:`~nowplan.acting.arrange.arrange` prefers them first;
* ``SelectParallelOps`` (Alg. 4) pulls later steps next to the chosen one
  while ``arrange`` says to combine them, up to a complexity limit, and
  ``CombineGoals`` makes their joint subgoal;
* every move is kept only if the reordered plan is still valid: its
  pre-images, recomputed by regression from the plan's goal, chain back to
  a ``g0`` that the current belief satisfies.

The rewrite (Alg. 3 and 4) is :class:`~nowplan.acting.reorder.Reorderer`.
:class:`Peephole` is the ``peephole`` strategy switch: its ``next_step`` hook
rewrites the top frame's plan and returns the chosen step; for a combined
step it returns the last operator with the joint subgoal, after lowering
the level of the other combined operators in the frame's level map (Alg. 2,
lines 11–13), so the executive pushes one plan for the joint subgoal.  That
plan is searched without the random-serialization shortcut (the
``planner_config`` hook): the subgoals were combined because they share
resources, so their conjuncts are exactly the ones not to serialize.
"""

from __future__ import annotations

import gc
import logging
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

from nowplan.acting.gather import gather
from nowplan.acting.mechanisms import Mechanism, Switch, register_switch
from nowplan.acting.reorder import PeepholeConfig, PreimageKey, Reorderer, highest_applicable
from nowplan.acting.resources import resource_model
from nowplan.acting.truth import HoldsFn, TruthMemo
from nowplan.core.atoms import Goal
from nowplan.core.operators import Action
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.regression import PlannerConfig

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame

__all__ = ["Peephole", "PeepholeConfig"]  # the switch and its settings (the rewrite itself: acting/reorder.py)

log = logging.getLogger(__name__)

# entries of the run's pre-image table before it is cleared (a bound on its memory; a marsupial
# run of 10 packages regresses a few thousand)
_MAX_REGRESSED = 200_000


class Peephole(Mechanism):
    """RCHPN (Alg. 2) as executive hooks: reorder and combine before each step."""

    name = "peephole"

    def __init__(self, config: PeepholeConfig | None = None) -> None:
        self.config = config or PeepholeConfig()
        self.reorders = 0
        self.combinations = 0
        # combinations whose joint planning failed, and the action count they failed at: not
        # formed again until the belief changes (the planner would prove the same subgoal
        # unplannable again, at the cost of a full search each time)
        self._failed: list[frozenset[Any]] = []
        self._failed_at = -1
        # the complexity limit in this belief: lowered below the size of a combined subgoal whose
        # joint search ran out of nodes or time (seed 002 IV: the limit keeps the next level's
        # problems solvable), so that after at most max_combined - 1 such failures RCHPN plans
        # the steps one at a time, as HPN does
        self._cap = self.config.max_combined
        # the plan holding a combined step whose refinement failed below its joint subgoal: every
        # frame above it is popped, so that the combination is given up where it was made (popping
        # only the failing frame lets the plans in between lead back to the same failure)
        self._unwind_to: int | None = None
        # the highest true kernel found by ``applicable`` (frame, plan, actions taken, k)
        self._applicable: tuple[Any, Plan, int, int | None] | None = None
        # action keys of every combination whose joint planning failed in this run (``_fallout``)
        self._given_up: set[Any] = set()
        # each pre-image atom's order key and text for the rewritten plans' trace records
        # (``Plan.to_json``'s ``made``): consecutive rewrites share most atoms
        self._atom_text: dict[Any, Any] = {}
        # the validity chains' pre-images, shared by every Reorderer of the run (a pre-image does not
        # depend on the belief; the tails of the candidate orders are regressed again at each step)
        self._regressed: dict[PreimageKey, Any] = {}
        # atom truths in the current belief, shared by the highest true kernel of every frame and
        # the rewrite's tests until the belief's state changes
        self._truth: TruthMemo | None = None

    def _holds(self, ex: Executive) -> HoldsFn:
        """``Domain.holds`` in the executive's belief, memoised while its point state is the same."""
        if self._truth is None or self._truth.domain is not ex.domain:
            self._truth = TruthMemo(ex.domain)
        return self._truth.holds_in(ex.belief)

    def _failed_now(self, ex: Executive) -> list[frozenset[Any]]:
        """The combinations that failed in the current belief (forgotten after each action)."""
        if self._failed_at != ex.metrics.actions:
            self._failed, self._failed_at = [], ex.metrics.actions
            self._cap = self.config.max_combined
        return self._failed

    def after_push(self, ex: Executive, frame: Frame) -> None:
        frame.info["orig"] = list(range(len(frame.plan.steps)))
        if len(ex.stack) >= 2 and ex.stack[-1] is frame:
            below = ex.stack[-2]
            under = _combination(below)
            if under is not None:
                frame.info["under_joint"] = under  # a refinement of a combined step, at any depth
                frame.info["joint_owner"] = _owner(below)

    def applicable(self, ex: Executive, frame: Frame) -> bool | None:
        if frame.root:
            return None
        if self._unwind_to is not None:
            if frame.plan_id == self._unwind_to or all(f.plan_id != self._unwind_to for f in ex.stack):
                self._unwind_to = None
            else:
                return False  # above a combination given up: popped (as not applicable)
        if frame.i >= frame.n:
            return False
        k = highest_applicable(ex.domain, ex.belief, frame.plan, _watch(frame), self._holds(ex))
        # the executive asks next_step right after this, in the same belief: it reuses k
        self._applicable = (frame, frame.plan, ex.metrics.actions, k)
        if k is None:
            return False
        if k == frame.n:  # the plan's goal already holds: done
            frame.i = frame.n
            return False
        return True

    def next_step(self, ex: Executive, frame: Frame) -> PlanStep | None:
        if frame.root:
            return None
        # the collector is paused while the tail is rewritten, as during a planner call: the
        # estimates and the shareability tests (bay searches) allocate many small acyclic objects
        paused = gc.isenabled()
        if paused:
            gc.disable()
        try:
            return self._next_step(ex, frame)
        finally:
            if paused:
                gc.enable()

    def _next_step(self, ex: Executive, frame: Frame) -> PlanStep | None:
        own = frame.info.pop("own_levels", None)
        if own is not None:
            # the combined operators were lowered for their joint refinement only (Alg. 2 lines
            # 11-13): every later choice, and a step refined alone after the combination was given
            # up, starts from the plan's own levels, so no step skips the levels at which its
            # vehicle's travel is planned before its loader work
            frame.plan = replace(frame.plan, levels=own)
        plan = frame.plan
        known, self._applicable = self._applicable, None
        if known is not None and known[0] is frame and known[1] is plan and known[2] == ex.metrics.actions:
            k = known[3]
        else:
            k = highest_applicable(ex.domain, ex.belief, plan, _watch(frame), self._holds(ex))
        if k is None or k >= frame.n:
            return None
        first = plan.steps[k + 1].action
        if first is not None and not _arrangeable(ex, plan, first):
            # nothing to rewrite (a primitive step or one the domain does not let move): the step
            # after the highest true kernel, as the rewrite below would choose it, without it
            frame.i = k + 1
            frame.info["fallout"] = frame.info["joint"] = frame.info["joint_ops"] = None
            return frame.plan.steps[frame.i]
        ops = [s.action for s in plan.steps[k + 1 :] if s.action is not None]
        before = list(ops)
        goals = [s.goal for s in plan.steps[k:]]
        failed = self._failed_now(ex)
        config = self.config
        if self._cap < config.max_combined:
            config = replace(config, max_combined=self._cap)
        if len(self._regressed) > _MAX_REGRESSED:
            self._regressed.clear()
        r = Reorderer(ex.domain, ex.problem.objects, ex.belief, plan.levels, config=config, failed=failed,
                      planner=ex.strategy.planner, regressed=self._regressed, holds=self._holds(ex))
        last = 0
        if r.arrangeable(ops[0]):
            ops, goals = r.select_gap(ops, goals)
            ops, goals, last = r.select_parallel_ops(ops, goals)
            ops, goals, last = gather(r, ops, goals, last)
        if r.moves:
            orig = frame.info.get("orig") or list(range(len(plan.steps)))
            frame.info["orig"] = [*orig[: k + 1], *_permuted(orig[k + 1 :], before, ops)]
            levels = plan.levels
            for a in ops[:last]:
                levels = levels.next_level(a)  # Alg. 2 lines 11-13
            if last > 0:
                frame.info["own_levels"] = plan.levels
            steps = [*plan.steps[:k], PlanStep(plan.steps[k].action, goals[0])]
            steps += [PlanStep(a, g) for a, g in zip(ops, goals[1:], strict=True)]
            frame.plan = replace(plan, steps=tuple(steps), levels=levels)
            self.reorders += sum(1 for m in r.moves if m.startswith("moved"))
            self.combinations += last
            ex.trace.emit(
                "note", text="peephole: " + "; ".join(r.moves), plan_id=frame.plan_id,
                peephole={"start": k, "order": frame.info["orig"], "combined": last + 1,
                          "steps": frame.plan.to_json(self._atom_text)},
            )
            log.info("peephole on plan %d: %s", frame.plan_id, "; ".join(r.moves))
        frame.i = k + 1 + last
        frame.info["fallout"] = frame.i if last == 0 and self._fallout(r, ops[0]) else None
        frame.info["joint"] = frame.i if last > 0 else None
        frame.info["joint_ops"] = frozenset(a.key for a in ops[: last + 1]) if last > 0 else None
        return frame.plan.steps[frame.i]

    def _fallout(self, r: Reorderer, step: Action) -> bool:
        """A step taken alone that was part of a combination given up earlier in this run: its
        refinement gets ``fallout_nodes`` (``planner_config``)."""
        return self.config.fallout_nodes > 0 and step.key in self._given_up and r.arrangeable(step)

    def after_plan_failure(self, ex: Executive, parent: Frame, goal: Goal, result: PlanResult) -> None:
        """A combined subgoal with no plan: remember the combination until the next action."""
        ops = _combination(parent)
        if ops is None:
            return
        self._failed_now(ex).append(ops)
        self._given_up.update(ops)
        too_big = result.status in (PlanStatus.TIME_LIMIT, PlanStatus.NODE_LIMIT)
        if too_big:
            self._cap = min(self._cap, len(ops) - 1)
        owner = _owner(parent)
        below = owner is not None and owner != parent.plan_id
        if below:
            self._unwind_to = owner
        ex.trace.emit("note", plan_id=parent.plan_id,
                      text=f"peephole: combined subgoal of {len(ops)} steps has no plan "
                           f"({result.status.value}); not combined again until the next action"
                           + (f", nor more than {self._cap} steps" if too_big else "")
                           + (f"; the plans above plan {owner}, which combined them, are given up"
                              if below else ""))

    def planner_config(
        self, ex: Executive, parent: Frame, goal: Goal, config: PlannerConfig
    ) -> PlannerConfig | None:
        """Combined subgoals are planned jointly: no random serialization of their conjuncts.

        Every search below a combined step (the joint subgoal and its refinements) is bounded
        by ``joint_nodes``: a combination whose refinement is not found within it is given up
        in this belief (``after_plan_failure``) and the steps are refined one at a time.
        """
        joint = parent.info.get("joint")
        out = None
        if self.config.joint_search and joint is not None and joint == parent.i:
            out = replace(config, serialization=False, weight=self.config.joint_weight)
        below = _combination(parent) is not None
        cap = self.config.joint_nodes
        if cap > 0 and below:
            base = out or config
            out = replace(base, max_nodes=min(base.max_nodes, cap), shortcut_nodes=min(base.shortcut_nodes, cap),
                          call_nodes=cap)
        fallout = self.config.fallout_nodes
        if not below and fallout > 0 and parent.info.get("fallout") == parent.i:
            base = out or config
            out = replace(base, max_nodes=min(base.max_nodes, fallout),
                          shortcut_nodes=min(base.shortcut_nodes, fallout), call_nodes=fallout)
        if below and not self.config.held_rewrites:
            out = replace(out or config, held_rewrites=False)
        return out


def _arrangeable(ex: Executive, plan: Plan, a: Action) -> bool:
    """:meth:`Reorderer.arrangeable` without a Reorderer (most steps are primitive)."""
    if plan.levels.is_primitive(a):
        return False
    names = resource_model(ex.domain).arrangeable
    return names is None or a.name in names


def _watch(frame: Frame) -> dict[int, Any]:
    """The frame's watched atoms for :func:`highest_applicable`, for the plan it holds now (a
    rewritten plan starts with none)."""
    known = frame.info.get("watch")
    if known is None or known[0] is not frame.plan:
        known = frame.info["watch"] = (frame.plan, {})
    watch: dict[int, Any] = known[1]
    return watch


def _combination(frame: Frame) -> frozenset[Any] | None:
    """The combined step ``frame`` is refining now, or the one it was pushed under (action keys)."""
    joint = frame.info.get("joint")
    if joint is not None and joint == frame.i and frame.info.get("joint_ops") is not None:
        return frozenset(frame.info["joint_ops"])
    under = frame.info.get("under_joint")
    return frozenset(under) if under is not None else None


def _owner(frame: Frame) -> int | None:
    """The plan id of the frame holding the combined step ``frame`` refines now or is pushed under."""
    joint = frame.info.get("joint")
    if joint is not None and joint == frame.i and frame.info.get("joint_ops") is not None:
        return frame.plan_id
    owner = frame.info.get("joint_owner")
    return int(owner) if owner is not None else None


def _permuted(labels: Sequence[int], before: Sequence[Action], after: Sequence[Action]) -> list[int]:
    """The labels of ``before``'s positions, in the order the same actions have in ``after``."""
    free = list(zip(before, labels, strict=True))
    out: list[int] = []
    for a in after:
        i = next(i for i, (b, _) in enumerate(free) if b == a)
        out.append(free.pop(i)[1])
    return out


register_switch(
    Switch(
        "peephole",
        "RCHPN: reorder and combine abstract subgoals by resource use before each step (seed 002)",
        mechanism=lambda s: Peephole(),
    )
)
