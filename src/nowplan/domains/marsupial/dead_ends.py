"""A cheap proof that a subgoal has no plan at its level: a package the loader cannot dig out.

What the regression search proves only by exhausting its space (3 000-10 000 expansions on the
marsupial runs of seed 002, where RCHPN's planner calls below and after a given-up combination ran
to their 500-node budget): the goal asks ``at(p, l)`` of a package ``p`` inside vehicle ``v``,
``v`` stands at ``l`` now, the refinement's ``unload(p, v, l)`` sits at a level that keeps its
``door(v) = p`` precondition, ``door(v)`` is not ``p`` now, and the loader's fetch of ``p`` from
``v``'s bay as it is now is proved impossible (every reachable configuration closed, or the relaxed
test of :mod:`.bay_relaxed`).

Why no plan then exists at that level, for the search as the domain's generators drive it.  Take
the earliest step of a plan that makes ``at(p, l)`` true; it is an ``unload(p, v', l)``.

* ``v' = v``: that instance keeps ``door(v) = p``, so some earlier step made it true.  The robot
  operators' arguments are transitions of loader paths from the bay as it is now (the generators
  read the belief), none of which reaches ``p`` at the door; so it was a ``load(p, v, y)``, whose
  place the ``load_place`` generator fixes to where ``p`` is now, ``l`` (``v`` stands there and
  can go there), and which needs ``at(p, l)`` earlier still.
* ``v' != v``: ``in(p, v')`` came from a ``load(p, v', y)``; ``v'`` can go to ``l`` (the unload
  needs ``reachable(l, v')``, kept at every level), so ``y`` is again ``l`` and ``at(p, l)`` held
  earlier.

Either way an earlier step made ``at(p, l)`` true, against the choice of the earliest.  (``at(p, l)``
is false now: ``p`` is in ``v``.)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.bay_relaxed import fetch_infeasible

DOOR_CRITICALITY = 2  # ``door(v) = p`` in Unload's preconditions (model.BAY)


def buried_package(goal: Any, belief: Any, levels: Any, objects: Mapping[str, str | None]) -> str | None:
    """Why ``goal`` has no plan at ``levels`` from ``belief`` (see the module), or None."""
    inside: dict[Any, Any] | None = None
    where: dict[Any, Any] | None = None
    for a in goal.atoms:
        if a.predicate != "at" or a.value is not True:
            continue
        if inside is None:
            inside = {args[0]: args[1] for args in belief.facts("in")}
        pkg, place = a.args
        veh = inside.get(pkg)
        if veh is None or levels.level_of(("unload", (pkg, veh, place))) >= DOOR_CRITICALITY:
            continue
        if where is None:
            where = {args[0]: args[1] for args in belief.facts("at")}
        if where.get(veh) != place or str(belief.value(("door", (veh,)))) == str(pkg):
            continue
        start = (belief.value(("cargo", (veh,))), lp.door_of(str(belief.value(("door", (veh,)))),
                                                            dict(belief.facts("shape"))))
        mode = f"fetch:{pkg}"
        # the generators' own call (model._transition), so its answer is theirs and is cached for them
        lp.CACHE.path(start, mode, lp.fetch_goal(str(pkg)), lp.fetch_h(str(pkg)),
                      infeasible=lambda c: fetch_infeasible(c[0], c[1], str(pkg)))
        if lp.CACHE.impossible(start, mode):
            return (f"{pkg} cannot leave {veh} at {place}: the loader cannot fetch it to the door from the bay "
                    f"as it is, and unload({pkg}, {veh}, {place}) needs door({veh}) = {pkg} at this level")
    return None
