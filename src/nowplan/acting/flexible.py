"""Flexible execution (seed 000 Fig. 4): retry steps and jump ahead on surprises.

A plan is applicable while the belief lies in *some* pre-image
``g_0 … g_{n-1}`` and not yet in ``g_n``; the next step is the one after the
rightmost pre-image that contains the belief.  A step whose result did not
come about is retried if its pre-image still holds (a disappointment); a
step made unnecessary by luck is skipped (a surprise).
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

    def applicable(self, ex: Executive, frame: Frame) -> bool | None:
        if frame.root:
            return None
        if ex.domain.satisfies(ex.belief, frame.plan.goal):
            return False
        return rightmost(ex, frame) is not None

    def next_step(self, ex: Executive, frame: Frame) -> PlanStep | None:
        i = rightmost(ex, frame)
        if i is None:
            return None
        frame.i = i + 1
        return frame.plan.steps[frame.i]


register_switch(
    Switch("flexible", "retry a step whose pre-image still holds; jump ahead on surprises (Fig. 4)",
           mechanism=lambda s: Flexible())
)
