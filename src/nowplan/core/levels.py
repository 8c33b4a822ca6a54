"""Abstraction levels over operator instances (seed 002 II-B).

``abs(op, i)`` keeps the preconditions of criticality ``> i``.  A level map
``α`` assigns a level to each operator instance; instances not in the map
sit at the domain's top (most abstract) level.  ``NextLevel(α, ω)`` lowers
ω's level just enough to add its next criticality class; an instance whose
level keeps all its preconditions is primitive (concrete).

Refining ω (:meth:`LevelMap.refinement`, seed 002 Alg. 1 line 7 and Alg. 2 line 14) also
lowers a *floor* for ω's operator: in the plans that refine ω,
no instance of that operator is more abstract than ω has become.  Without it a
refinement can swap ω for a sibling instance that still hides the preconditions
just exposed (pieces: refining ``move_arm(a, b)`` plans ``move_arm(c, b)`` from a
cell ``c`` nearer ``b``, whose ``arm_at(c)`` is hidden again), and each such swap
pushes another plan: a refinement recursion as long as there are siblings.  With
the floor every refinement lowers one operator's floor by at least one criticality
class, so a chain of refinements is at most as deep as the operators have criticality
classes in all.
"""

from __future__ import annotations

from dataclasses import dataclass

from nowplan.core.operators import Action

ActionKey = tuple[str, tuple[object, ...]]


@dataclass(frozen=True)
class LevelMap:
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

    def refinement(self, action: Action) -> LevelMap:
        """The levels at which the abstract step ω is refined: :meth:`next_level`, and ω's operator
        floored at ω's new level (no instance of it more abstract in the plans below)."""
        out = self.next_level(action)
        new = out.level(action)
        name = action.key[0]
        fl = self.floor(name)
        if fl is not None and fl <= new:
            return out
        return LevelMap(out.top, out.overrides, frozenset({(n, v) for n, v in self.floors if n != name} | {(name, new)}))

    def describe(self, action: Action) -> int:
        """How many criticality classes of ω are still hidden at its level (0 = primitive)."""
        cur = self.level(action)
        return sum(1 for c in action.operator.criticalities if c <= cur)


def initial_levels(top: int) -> LevelMap:
    return LevelMap(top)


def flat_levels() -> LevelMap:
    """A level map at which every instance is primitive (criticalities are >= 0)."""
    return LevelMap(-(10**9))
