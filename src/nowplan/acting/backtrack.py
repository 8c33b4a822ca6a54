"""Backtracking across abstraction levels when a refinement fails (seed 002 Sec. II).

Committing to an abstract plan is only safe under the downward refinement
property; when the planner finds no plan for the subgoal of an abstract step
ω (the step cannot be refined from the current belief), HPN must backtrack
across levels instead of re-issuing ω.  The executive learns a *nogood*:
"from this belief, a plan for goal γ at level map α must not start with ω",
pops the plan that contained ω, and has its parent refine the same step
again, i.e. plan γ at α again with ω forbidden as a first step.  If no other
first step exists, that refinement fails in turn and the nogood is learnt
one level up, and so on to the root, whose failure ends the run with the
planner's reason.

Nogoods hold for the belief they were learnt in: every action clears them
(the world, or what is known of it, has changed and ω may be refinable
again).  Each failed refinement adds one nogood and there are finitely many
first steps per (goal, level map), so between two actions the backtracking
ends; the executive's refinement bound stays as the last guard.
"""

from __future__ import annotations

from collections.abc import Hashable
from dataclasses import dataclass, field

from nowplan.core.atoms import Goal
from nowplan.core.levels import LevelMap


@dataclass
class Nogoods:
    """First steps learnt not to be refinable, per (goal, level map), until the next action."""

    table: dict[tuple[Goal, LevelMap], set[Hashable]] = field(default_factory=dict)

    def learn(self, goal: Goal, levels: LevelMap, first: Hashable) -> None:
        self.table.setdefault((goal, levels), set()).add(first)

    def forbidden(self, goal: Goal, levels: LevelMap) -> frozenset[Hashable]:
        return frozenset(self.table.get((goal, levels), ()))

    def clear(self) -> None:
        self.table.clear()

    def __len__(self) -> int:
        return sum(len(v) for v in self.table.values())
