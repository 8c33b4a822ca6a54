"""Regions a placement must avoid.

* *taboo* regions (foresight, seed 000 III-B): every region some plan on
  the stack needs clear; avoided when possible;
* *hard* regions: the region being cleared, every region the goal being
  planned needs clear of the object, and (``Keep``) where a manipulation
  later in the same plan drives or drags: putting the object there would
  block that manipulation (local foresight, carried by regression).
"""

from __future__ import annotations

import math
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.domains.namo.generators import foresight
from nowplan.domains.namo.geometry import Manip, Region


def taboo_regions(context: Any) -> list[Region]:
    """Every region some plan on the stack needs clear: its BClear requirements and its moves' volumes."""
    if not foresight(context):
        return []
    out: dict[Region, None] = {}
    for a in context.requirements("BClear"):
        if isinstance(a.args[0], Region):
            out[a.args[0]] = None
    for plan in context.plan_stack:
        for step in plan.steps:
            act = step.action
            if act is None:
                continue
            for pre in act.preconditions(None):
                if pre.predicate == "BClear" and isinstance(pre.args[0], Region):
                    out[pre.args[0]] = None
    return list(out)


def hard_regions(goal: Goal, obj: str, cleared: Region) -> list[Region]:
    """Where ``obj`` must not be put: the region cleared, regions the goal needs clear of it, and
    where a later manipulation in the plan drives or drags (``Keep``)."""
    out = [cleared]
    for a in goal.atoms:
        if a.predicate == "Keep" and a.args[1] != obj and isinstance(a.args[0], tuple):
            out.extend(r for r in a.args[0] if isinstance(r, Region))
        ex = a.args[1] if a.predicate == "BClear" else frozenset()
        if a.predicate == "BClear" and isinstance(a.args[0], Region) and isinstance(ex, frozenset) and obj not in ex:
            if a.args[0] != cleared:
                out.append(a.args[0])
    return out


def kept_regions(m: Manip, size: tuple[float, float], r: float) -> tuple[Region, ...]:
    """The volumes a manipulation needs free of other placed objects: the robot along the pick, carry
    and return paths, and the object's own sweep."""
    out = [Region(p, q, r) for path in (m.pick_path, m.carry_path, m.return_path) for p, q in zip(path, path[1:])]
    out.append(Region(m.obj_at, m.place, math.hypot(*size) / 2))
    return tuple(out)
