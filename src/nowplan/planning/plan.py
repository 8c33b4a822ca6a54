"""Plans with their pre-images, and planner results.

A plan is ``[(None, g0), (ω1, g1), …, (ωn, gn)]`` (seed 002 II-C, seed 000
II-A): ``gn`` is the goal, ``g(i-1)`` is the pre-image of ``g(i)`` under
``ωi`` at the plan's abstraction level, and the belief the plan was made in
satisfies ``g0``.
"""

from __future__ import annotations

import enum
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Goal, atom_order
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action


class PlanStatus(enum.Enum):
    """How a planning call ended."""

    SOLVED = "solved"
    UNSOLVABLE = "unsolvable"
    NODE_LIMIT = "node_limit"
    TIME_LIMIT = "time_limit"


@dataclass(frozen=True)
class PlanStep:
    action: Action | None
    goal: Goal  # g_i: holds after this step if g_(i-1) held before it

    def __iter__(self) -> Iterator[Any]:
        yield self.action
        yield self.goal


@dataclass(frozen=True)
class Plan:
    steps: tuple[PlanStep, ...]
    levels: LevelMap

    def __post_init__(self) -> None:
        if not self.steps or self.steps[0].action is not None:
            raise ValueError("a plan starts with (None, g0)")

    @property
    def goal(self) -> Goal:
        return self.steps[-1].goal

    @property
    def actions(self) -> tuple[Action, ...]:
        return tuple(s.action for s in self.steps[1:] if s.action is not None)

    def preimage(self, i: int) -> Goal:
        """``g_i``; ``preimage(0)`` is ``g0``."""
        return self.steps[i].goal

    def __len__(self) -> int:
        """Number of operator steps n."""
        return len(self.steps) - 1

    def cost(self, belief: Any = None) -> float:
        return sum(a.cost(belief) for a in self.actions)

    def level_of(self, i: int) -> int:
        a = self.steps[i].action
        return self.levels.level(a) if a is not None else self.levels.top

    def is_primitive(self, i: int) -> bool:
        a = self.steps[i].action
        return a is not None and self.levels.is_primitive(a)

    def to_json(self, made: dict[Any, Any] | None = None) -> list[dict[str, Any]]:
        """The plan's trace record (docs/trace-format.md).  ``made``: each atom's order key and text and
        each goal's text (:func:`goal_text`), kept by the caller across plans (the executive's plans
        share most pre-image atoms, and a refinement's last pre-image is its parent step's)."""
        out: list[dict[str, Any]] = []
        # consecutive preimages share most atoms: each atom's order key and text are made once per plan
        # or per ``made`` (the order is Goal.__iter__'s, the text str(atom))
        if made is None:
            made = {}

        def written(goal: Goal) -> list[str]:
            return goal_text(goal, made)

        for i, s in enumerate(self.steps):
            a = s.action
            out.append(
                {
                    "index": i,
                    "action": a.pddl() if a is not None else None,
                    "level": self.levels.level(a) if a is not None else None,
                    "primitive": bool(a is not None and self.levels.is_primitive(a)),
                    "hidden": self.levels.describe(a) if a is not None else 0,
                    "preimage": written(s.goal),
                }
            )
        return out


def goal_text(goal: Goal, made: dict[Any, Any]) -> list[str]:
    """``[str(a) for a in goal]`` (in :meth:`Goal.__iter__`'s order), each atom's order key and text
    kept in ``made`` for the next goals (pre-images share most of their atoms), and each goal's list
    too: a refinement's last pre-image is the goal of the step it refines, already written (gripper,
    250 balls, --criticality auto: 2501 goals written, 2.3 s of a 20.9 s profile).  The list is
    shared between the records that show the goal: not to be changed."""
    hit = made.get(goal)
    if hit is not None:
        return hit  # type: ignore[no-any-return]
    rows = []
    for x in goal.atoms:
        t = made.get(x)
        if t is None:
            t = made[x] = (atom_order(x), str(x))
        rows.append(t)
    rows.sort()  # (the keys differ between a goal's atoms: one atom per fluent and value)
    out = made[goal] = [text for _, text in rows]
    return out


@dataclass(frozen=True)
class PlanResult:
    """What a planner call returns; failure is a status with a reason, not an exception."""

    status: PlanStatus
    plan: Plan | None = None
    reason: str = ""
    expanded: int = 0
    generated: int = 0
    cpu_time_s: float = 0.0
    method: str = ""  # which search found it: serialization | monotonic | full
    attempts: tuple[str, ...] = field(default=())

    @property
    def solved(self) -> bool:
        return self.status is PlanStatus.SOLVED
