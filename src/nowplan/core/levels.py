"""Abstraction levels over operator instances (seed 002 II-B).

``abs(op, i)`` keeps the preconditions of criticality ``> i``.  A level map
``α`` assigns a level to each operator instance; instances not in the map
sit at the domain's top (most abstract) level.  ``NextLevel(α, ω)`` lowers
ω's level just enough to add its next criticality class; an instance whose
level keeps all its preconditions is primitive (concrete).

A map also has *floors*: operator -> the most abstract level any instance of it has.  The
executive sets them (:meth:`LevelMap.floored`) when a plan made to refine ω contains an
instance of an operator more abstract than an instance of it refined higher up the chain, and
plans that refinement again.  Without floors a refinement can swap the step just made more
concrete for a sibling instance that hides the exposed precondition again (pieces: refining
``move_arm(a, b)`` chose an abstract ``move_arm(c, b)`` from a cell ``c`` nearer ``b``, then
the same from ``c``), one pushed plan per sibling.  With them, along a chain of refinements
each push lowers the lowest refined level of one operator by at least one criticality class,
so the chain is no deeper than the operators have classes in all.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from nowplan.core.operators import Action

ActionKey = tuple[str, tuple[object, ...]]


@dataclass(frozen=True)
class LevelMap:
    """A level per operator instance: ``top`` for all but the ``overrides``, with the ``floors`` of
    the refinements above (see the module docstring); ``LevelMap(domain.top_level)`` is the
    hierarchy's top, :func:`flat_levels` a map at which every instance is concrete."""

    top: int
    overrides: frozenset[tuple[ActionKey, int]] = frozenset()
    # operator name -> the most abstract level any of its instances has (set by next_level)
    floors: frozenset[tuple[str, int]] = frozenset()

    def __post_init__(self) -> None:
        object.__setattr__(self, "_table", dict(self.overrides))
        object.__setattr__(self, "_floors", dict(self.floors))

    def level(self, action: Action) -> int:
        lv: int = self._table.get(action.key, self.top)  # type: ignore[attr-defined]
        floors: dict[str, int] = self._floors  # type: ignore[attr-defined]
        if floors:
            fl = floors.get(action.key[0])
            if fl is not None and fl < lv:
                return fl
        return lv

    def level_of(self, key: ActionKey) -> int:
        """:meth:`level` of the instance with this key (operator name, arguments), for a caller
        that has no :class:`Action` built."""
        lv: int = self._table.get(key, self.top)  # type: ignore[attr-defined]
        fl = self._floors.get(key[0])  # type: ignore[attr-defined]
        return fl if fl is not None and fl < lv else lv

    def floor(self, operator: str) -> int | None:
        """The most abstract level an instance of ``operator`` has here (None: no floor)."""
        return self._floors.get(operator)  # type: ignore[attr-defined, no-any-return]

    def is_primitive(self, action: Action) -> bool:
        return action.is_primitive(self.level(action))

    def next_level(self, action: Action) -> LevelMap:
        """``NextLevel(α, ω)``: ω one criticality class more concrete."""
        cur = self.level(action)
        lower = [c for c in action.operator.criticalities if c <= cur]
        new = (max(lower) - 1) if lower else cur
        rest = frozenset((k, v) for k, v in self.overrides if k != action.key)
        return LevelMap(self.top, rest | {(action.key, new)}, self.floors)

    def floored(self, actions: Iterable[Action]) -> LevelMap:
        """This map with a floor for each operator of which one of ``actions`` is more abstract than an
        instance already lowered here (an override, i.e. refined higher up the chain), at that
        instance's level; ``self`` when there is none."""
        lowest: dict[str, int] = {}
        for key, lv in self.overrides:
            if lv < lowest.get(key[0], self.top):
                lowest[key[0]] = lv
        floors: dict[str, int] = dict(self._floors)  # type: ignore[attr-defined]
        changed = False
        for a in actions:
            name = a.key[0]
            lo = lowest.get(name)
            if lo is not None and self.level(a) > lo:
                floors[name] = lo
                changed = True
        return LevelMap(self.top, self.overrides, frozenset(floors.items())) if changed else self

    def describe(self, action: Action) -> int:
        """How many criticality classes of ω are still hidden at its level (0 = primitive)."""
        cur = self.level(action)
        return sum(1 for c in action.operator.criticalities if c <= cur)


def initial_levels(top: int) -> LevelMap:
    return LevelMap(top)


def flat_levels() -> LevelMap:
    """A level map at which every instance is primitive (criticalities are >= 0)."""
    return LevelMap(-(10**9))
