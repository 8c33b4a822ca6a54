"""What generators and the planner may see beyond the goal and the belief."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom
from nowplan.planning.plan import Plan


@dataclass(frozen=True)
class PlanningContext:
    """The plan stack (outermost first) for foresight, plus free-form extras.

    ``extras["foresight"]`` tells generators whether foresight is on; without
    foresight the executive passes an empty stack.

    Seed 000 replaces line 10 of Fig. 2 so the planner receives the whole
    plan stack: generators can then avoid regions that later subgoals need.
    """

    plan_stack: tuple[Plan, ...] = ()
    extras: Mapping[str, Any] = field(default_factory=dict, hash=False, compare=False)

    @property
    def foresight(self) -> bool:
        return bool(self.extras.get("foresight", False))

    @property
    def whole_problem(self) -> bool:
        """``extras["whole_problem"]``: the call plans the whole problem flat (a flat strategy, the online
        policy): no level above plans again if it fails (see :mod:`nowplan.acting.whole`)."""
        return bool(self.extras.get("whole_problem", False))

    @property
    def restricted(self) -> bool:
        """``extras["restricted"]``: the second pass of a whole-problem call, in which a domain's
        generators may restrict what they offer as they do in a refinement (:mod:`nowplan.acting.whole`)."""
        return bool(self.extras.get("restricted", False))

    def requirements(self, predicate: str | None = None) -> list[Atom]:
        """Atoms (of ``predicate``, or all) required by pre-images of the stack's plans.

        With foresight these are the robot's intentions: a generator choosing,
        say, where to put an object avoids every region some plan on the stack
        still needs clear (seed 000 III-B, the *taboo* regions).
        """
        seen: set[Atom] = set()
        out: list[Atom] = []
        for p in self.plan_stack:
            for s in p.steps:
                for a in s.goal:
                    if (predicate is None or a.predicate == predicate) and a not in seen:
                        seen.add(a)
                        out.append(a)
        return out
