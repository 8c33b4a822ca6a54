"""Flexible execution (seed 000 Fig. 4): retry steps and jump ahead on surprises.

A plan is applicable while the belief lies in *some* pre-image
``g_0 … g_{n-1}`` and not yet in ``g_n``; the next step is the one after the
rightmost pre-image that contains the belief.  A step whose result did not
come about is retried if its pre-image still holds (a disappointment); a
step made unnecessary by luck is skipped (a surprise).

Retrying is for outcomes that vary: once a plan has gone back
``Strategy.max_retries`` times (default 2) (taken a step again, or an earlier one, because a step did not have
its result: a move blocked by the same object, a drag stopped by the same
wall), the next setback is not retried: for the rest of that action the
rigid rules apply, so the plans whose steps did not have their results are
popped and the goal is replanned from the belief as it is (the original
BHPN's failure handling), instead of retrying until a budget runs out.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.mechanisms import Mechanism, Switch, register_switch

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive, Frame
    from nowplan.planning.plan import PlanStep


def rightmost(ex: Executive, frame: Frame) -> int | None:
    """``argmax_{i < n} b ∈ g_i``, or None when the belief is in no pre-image before the end."""
    for i in range(frame.n - 1, -1, -1):
        if ex.domain.satisfies(ex.belief, frame.plan.preimage(i)):
            return i
    return None


class Flexible(Mechanism):
    name = "flexible"

    def __init__(self, max_retries: int = 2) -> None:
        self.max_retries = max_retries  # setbacks a plan may retry before it is replanned
        self._rigid_at: int | None = None  # action count at which a retry was last given up

    def applicable(self, ex: Executive, frame: Frame) -> bool | None:
        if frame.root:
            return None
        if ex.domain.satisfies(ex.belief, frame.plan.goal):
            return False
        if self._rigid_at == ex.metrics.actions:
            return None  # a retry was given up since the last action: rigid rules
        i = rightmost(ex, frame)
        if i is None:
            return False
        if i + 1 <= frame.i and frame.info.get("retries", 0) >= self.max_retries:
            ex.trace.emit("note", plan_id=frame.plan_id,
                          text=f"flexible: plan set back {self.max_retries} times already; replanning")
            self._rigid_at = ex.metrics.actions
            return None
        return True

    def next_step(self, ex: Executive, frame: Frame) -> PlanStep | None:
        i = rightmost(ex, frame)
        if i is None:
            return None
        if i + 1 <= frame.i:  # a step taken again, or an earlier one: a setback
            frame.info["retries"] = frame.info.get("retries", 0) + 1
        frame.i = i + 1
        return frame.plan.steps[frame.i]


register_switch(
    Switch("flexible", "retry a step whose pre-image still holds; jump ahead on surprises (Fig. 4)",
           mechanism=lambda s: Flexible(s.max_retries))
)
