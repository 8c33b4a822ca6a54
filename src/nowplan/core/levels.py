"""Abstraction levels over operator instances (seed 002 II-B).

``abs(op, i)`` keeps the preconditions of criticality ``> i``.  A level map
``α`` assigns a level to each operator instance; instances not in the map
sit at the domain's top (most abstract) level.  ``NextLevel(α, ω)`` lowers
ω's level just enough to add its next criticality class; an instance whose
level keeps all its preconditions is primitive (concrete).
"""

from __future__ import annotations

from dataclasses import dataclass

from nowplan.core.operators import Action

ActionKey = tuple[str, tuple[object, ...]]


@dataclass(frozen=True)
class LevelMap:
    top: int
    overrides: frozenset[tuple[ActionKey, int]] = frozenset()

    def __post_init__(self) -> None:
        object.__setattr__(self, "_table", dict(self.overrides))

    def level(self, action: Action) -> int:
        return self._table.get(action.key, self.top)  # type: ignore[attr-defined, no-any-return]

    def is_primitive(self, action: Action) -> bool:
        return action.is_primitive(self.level(action))

    def next_level(self, action: Action) -> LevelMap:
        """``NextLevel(α, ω)``: ω one criticality class more concrete."""
        cur = self.level(action)
        lower = [c for c in action.operator.criticalities if c <= cur]
        new = (max(lower) - 1) if lower else cur
        rest = frozenset((k, v) for k, v in self.overrides if k != action.key)
        return LevelMap(self.top, rest | {(action.key, new)})

    def describe(self, action: Action) -> int:
        """How many criticality classes of ω are still hidden at its level (0 = primitive)."""
        cur = self.level(action)
        return sum(1 for c in action.operator.criticalities if c <= cur)


def initial_levels(top: int) -> LevelMap:
    return LevelMap(top)


def flat_levels() -> LevelMap:
    """A level map at which every instance is primitive (criticalities are >= 0)."""
    return LevelMap(-(10**9))
