"""Deferred successors in the regression search: the achievers of facts that already hold.

A subgoal of HPN's calls holds every goal fact of the objects the call does
not touch (a package already delivered, or waiting where it is); they hold in
the belief, yet A* regresses through each of their achievers too (the last
step of a plan may have to re-achieve a fact an earlier step undid), and
each such successor costs a pre-image, new facts to explore and an estimate.
Their number grows with the number of such objects, while they are almost
never expanded: a step that re-achieves a fact that holds adds its own cost
to every unmet fact's.

So when a node is expanded, the successors of the facts it asks for that do
not hold are made at once, and those of the facts that hold are grouped in
:class:`Deferred` entries of the frontier, with a lower bound on their
priority: ``g + cost + weight · b`` where ``b`` is the largest explored cost
of an unmet fact of the node whose fluent the action neither sets nor
requires (:func:`bound`), which the regression keeps in the child as it is;
the relaxed estimates the search uses with deferral (h_max, LM-cut, h_add)
are at least that.  An entry is opened (its successors made) only when it
comes first in the frontier, so the search expands what it would have
expanded eagerly, in the same order: children are stamped with the order
in which eager generation makes them, ``(expansion, target, achiever)``, and
the stamp breaks ties as eager generation's counter did (also between two
equally cheap paths to one subgoal).  The relaxation's exploration is lazy,
so its costs can fall between an expansion and the opening of its entries;
a bound that turns out too high only changes the order, never a plan's
validity.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

from nowplan.core.facts import FactTable
from nowplan.core.operators import Action
from nowplan.planning.subgoals import ActionFacts, NodeIndex

# eager generation order of a child: (parent's expansion number, target index, achiever index)
Stamp = tuple[int, int, int]
Item = tuple[Stamp, Action, ActionFacts, float]


class Deferred:
    """The held facts' successors of one node with one priority bound (a frontier entry)."""

    __slots__ = ("node", "focus", "g", "index", "goal_of", "items")

    def __init__(self, node: Any, focus: int, g: float, index: NodeIndex, goal_of: Callable[[], Any],
                 items: list[Item]) -> None:
        self.node = node
        self.focus = focus  # the children's focus (serialization)
        self.g = g
        self.index = index
        self.goal_of = goal_of
        self.items = items


class Touched:
    """The fluents an action sets or requires at its level (kept per :class:`ActionFacts` in one call)."""

    def __init__(self, table: FactTable) -> None:
        self.fluent = table.fluent
        self._memo: dict[int, tuple[ActionFacts, frozenset[int]]] = {}

    def __call__(self, info: ActionFacts) -> frozenset[int]:
        hit = self._memo.get(id(info))
        if hit is not None and hit[0] is info:
            return hit[1]
        fl = self.fluent
        out = frozenset([fl[e] for e in info.all_effs] + [fl[p] for p in info.pre])
        self._memo[id(info)] = (info, out)
        return out


def bound(unmet: Sequence[tuple[int, float]], touched: frozenset[int]) -> float:
    """The largest cost among ``unmet`` ``(fluent, cost)`` pairs whose fluent is not ``touched`` (0 if none)."""
    b = 0.0
    for flu, v in unmet:
        if v > b and flu not in touched:
            b = v
    return b


def group(items: Sequence[tuple[Item, float]]) -> dict[tuple[float, float], list[Item]]:
    """Items with their estimate's bound, by (cost, bound) (each list in stamp order); ``inf`` bounds dropped.

    An infinite bound means the child keeps a fact the relaxation proved
    unreachable: its estimate is ``inf`` and the search would not keep it.
    """
    out: dict[tuple[float, float], list[Item]] = {}
    for item, b in items:
        if b != math.inf:
            out.setdefault((item[3], b), []).append(item)
    return out
