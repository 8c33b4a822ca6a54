"""Serendipity (seed 000 Fig. 5, lines 1–4).

After every action, walk the plan stack from the most abstract plan down.
If a plan's goal already holds, it and every plan above it are popped: the
work they were doing is no longer needed (the paper's robot that finds the
cupboard already full "returns directly").  Otherwise, if the step a plan
would now take (the one after its rightmost pre-image holding in the
belief) is not the one the plan above it is working on, the world has moved
under us, so every plan above it is popped and execution resumes from that
step.

A resume goes *forward* only: the belief has reached a pre-image further along the
plan than the step being worked on, so the steps from there still reach the plan's
goal.  A plan whose rightmost holding pre-image lies *behind* the step being worked on
is not lucky: a sub-plan on its way (fetching a key, walking back through a room that
happens to satisfy an earlier pre-image) passes through such states, and resuming
there dropped the sub-plan and looped.  That plan stays; if the sub-plan cannot go on
it is popped by the ordinary rules.  While the executive is committed after a cycle
(:mod:`nowplan.acting.progress`) no step is resumed.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.flexible import rightmost
from nowplan.acting.mechanisms import Mechanism, Switch, register_switch

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive


class Serendipity(Mechanism):
    name = "serendipity"

    def after_action(self, ex: Executive) -> None:
        for idx in range(1, len(ex.stack) - 1):  # the root's step is always the goal itself
            frame, above = ex.stack[idx], ex.stack[idx + 1]
            if ex.domain.satisfies(ex.belief, frame.plan.goal):
                ex.trace.emit("note", plan_id=frame.plan_id, text="serendipity: goal already holds")
                while len(ex.stack) > idx:
                    ex.pop("serendipity")
                ex.serendipity_events += 1
                return
            if ex.committed:
                continue  # goals that came true are still popped above; no resumes
            i = rightmost(ex, frame)
            if i is None:
                continue  # not applicable any more: the ordinary pop handles it
            if i + 1 > frame.i and frame.plan.preimage(i + 1) != above.plan.goal:
                ex.trace.emit(
                    "note", plan_id=frame.plan_id,
                    text=f"serendipity: resume plan {frame.plan_id} at step {i + 1}",
                )
                while len(ex.stack) > idx + 1:
                    ex.pop("serendipity")
                frame.i = i  # its next step is i + 1, whatever the step rule
                ex.serendipity_events += 1
                return


register_switch(
    Switch("serendipity", "pop back to a more abstract plan whose next step changed (Fig. 5)",
           mechanism=lambda s: Serendipity())
)
