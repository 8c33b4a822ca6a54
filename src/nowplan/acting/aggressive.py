"""Aggressive replanning: replan from the root after every action (seed 000 IV).

With hysteresis: after the progress guard saw a cycle (:mod:`nowplan.acting.progress`,
e.g. a replan toward another item after every action that shuttles the robot between two
rooms) the executive is *committed* and the current plan is kept until it is finished or
fails; replanning after every action resumes then.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.mechanisms import Mechanism, Switch, register_switch

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive


class AggressiveReplan(Mechanism):
    name = "aggressive"

    def after_action(self, ex: Executive) -> None:
        if ex.committed:
            return
        if len(ex.stack) > 1 and not ex.goal_holds():
            while len(ex.stack) > 1:
                ex.pop("replaced")
            ex.request_replan("aggressive", "replan after every action")


register_switch(
    Switch("aggressive", "replan the whole goal after every action", mechanism=lambda s: AggressiveReplan())
)
