"""Aggressive replanning: replan from the root after every action (seed 000 IV)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from nowplan.acting.mechanisms import Mechanism, Switch, register_switch

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive


class AggressiveReplan(Mechanism):
    name = "aggressive"

    def after_action(self, ex: Executive) -> None:
        if len(ex.stack) > 1 and not ex.goal_holds():
            while len(ex.stack) > 1:
                ex.pop("replaced")
            ex.request_replan("aggressive", "replan after every action")


register_switch(
    Switch("aggressive", "replan the whole goal after every action", mechanism=lambda s: AggressiveReplan())
)
