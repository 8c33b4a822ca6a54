"""Selective replanning (seed 000 Fig. 5, lines 5–9).

After every action each plan on the stack, from the most abstract down, is
asked whether to reconsider it: by the domain's triggers
(``Domain.triggers``: ``fn(plan, belief) -> reason or None``, e.g. a newly
seen obstacle on the planned path) and by a cost-increase trigger that
re-evaluates the remaining steps' costs in the new belief (linear time)
against the costs cached when the plan was made.  A fired trigger replans
the plan's goal at its level from the current belief; if the new plan is
the same as, or a contiguous part of, the old one, execution goes on;
otherwise that plan and everything above it are popped and the new plan
takes its place.  While the executive is committed after a cycle
(:mod:`nowplan.acting.progress`) no trigger is followed: hysteresis.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.mechanisms import Mechanism, Switch, register_switch

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame
    from nowplan.acting.strategy import Strategy
    from nowplan.core.operators import Action


def is_part_of(new: tuple[Action, ...], old: tuple[Action, ...]) -> bool:
    """Is ``new`` equal to, or a contiguous sub-sequence of, ``old``?"""
    if not new:
        return True
    k = len(new)
    return any(old[j : j + k] == new for j in range(len(old) - k + 1))


def cost_increase(ex: Executive, frame: Frame, threshold: float) -> str | None:
    """Fire when the remaining steps now cost more than ``(1 + threshold)`` × their cached cost."""
    cached = frame.info.get("step_costs")
    if not cached:
        return None
    start = frame.i + 1
    steps = frame.plan.steps[start:]
    old = sum(cached[start:])
    new = sum(s.action.cost(ex.belief) for s in steps if s.action is not None)
    if new > old * (1.0 + threshold) + 1e-9:
        return f"remaining cost rose from {old:g} to {new:g}"
    return None


class Selective(Mechanism):
    name = "selective"

    def __init__(self, strategy: Strategy) -> None:
        self.threshold = strategy.cost_increase

    def trigger(self, ex: Executive, frame: Frame) -> str | None:
        for fn in ex.domain.triggers:
            reason = fn(frame.plan, ex.belief)
            if reason:
                return reason
        return cost_increase(ex, frame, self.threshold)

    def after_action(self, ex: Executive) -> None:
        if ex.committed:
            return
        top = ex.stack[-1] if ex.stack else None
        if top is not None and not top.root and not ex.domain.satisfies(ex.belief, top.plan.preimage(top.i)):
            # the step just taken did not have its intended result: the executive handles that
            # failure (pops the plan and replans from the belief as it is now), so replanning the
            # failing plans here first would plan the same goals twice
            return
        for idx in range(1, len(ex.stack)):
            frame = ex.stack[idx]
            reason = self.trigger(ex, frame)
            if reason is None:
                continue
            ex.trace.emit("note", plan_id=frame.plan_id, text=f"reconsider: {reason}")
            parent = ex.stack[idx - 1]
            ex.request_replan("reconsideration", reason)
            new = ex.make_plan(frame.plan.goal, frame.plan.levels, parent)
            if new is None:
                continue  # keep the old plan; the failure is traced
            remaining = frame.plan.actions[max(frame.i - 1, 0) :]
            if is_part_of(new.actions, remaining):
                ex.trace.emit("note", plan_id=frame.plan_id, text="new plan is part of the old one: keep it")
                continue
            while len(ex.stack) > idx:
                ex.pop("replaced")
            ex._pending_trigger = None  # the replacement below is this replan
            ex.push(new, parent)
            return


register_switch(
    Switch("selective", "replan a plan when a domain trigger or a cost increase fires (Fig. 5)",
           mechanism=lambda s: Selective(s))
)
