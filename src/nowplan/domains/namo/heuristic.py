"""A goal-distance estimate for NAMO subgoals, for the flat planner the online policy runs.

Without one, regression counts unmet atoms (each at the cheapest action
cost): under a noisy sensor every object's shadow blocks the way, and a
subgoal that needs seven looks and a drag scores like one that needs a
single look, so the search spreads over every ordering of looks, picks and
placements (domain 1 with sensor noise 0.08-0.1 m/m: 50 000 nodes without a
plan).  This estimate prices each unmet atom by what its cheapest achiever
costs from the current belief:

* ``RobotAt(p)`` — the straight-line distance from the robot (a move costs
  its length);
* ``BVRelPose(o) = e`` — the looks that take ``o``'s estimate to ``e`` from
  where the robot stands (:func:`~nowplan.domains.namo.generators.looks_needed`);
* ``BClear(R, ex)`` — for each object in the way: a drag (pick and place,
  at least 2) if its body meets ``R``, else the looks that shrink its shadow
  out of ``R``; an object counts once however many regions it blocks;
* ``Observed(R)`` — one look, plus the detour to its view point when the
  subgoal has the robot elsewhere (a look for a region further along the
  way must wait until the robot gets there);
* ``Holding(o, m)`` — the pick's cost; other achievable atoms — 1 (one action);
* ``Fits``, ``Promising``, ``OutOfWay`` — no action makes them true: an
  unmet one is a dead end (infinite).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.domains.namo.geometry import Manip, Pt, Region

# atoms no operator achieves: unmet in a subgoal, the subgoal cannot be reached
UNACHIEVABLE = frozenset({"Fits", "Promising", "OutOfWay"})
DRAG = 2.0  # a pick and a place cost at least 1 each


def estimate(goal: Goal, belief: Any, holds: Callable[[Atom], bool]) -> float:
    """The estimated cost of reaching ``goal`` from ``belief`` (``holds`` tests one atom)."""
    from nowplan.domains.namo.belief import k_of
    from nowplan.domains.namo.generators import _sigma_to_clear, look_noise, looks_needed

    total = 0.0
    here = belief.nominal()
    # where the subgoal has the robot (it is there at that point of the plan)
    there = next((a.args[0] for a in goal.atoms if a.predicate == "RobotAt" and a.value is True
                  and isinstance(a.args[0], Pt)), None)
    drags: set[str] = set()
    looks: dict[str, int] = {}
    for a in goal.atoms:
        if holds(a):
            continue
        p = a.predicate
        if p in UNACHIEVABLE:
            return math.inf
        if p == "RobotAt":
            if a.value is True and isinstance(a.args[0], Pt):
                total += here.dist(a.args[0])
        elif p == "Holding":
            m = a.args[1]
            total += 1.0 + (m.lengths[0] if isinstance(m, Manip) and a.value is True else 0.0)
        elif p == "BVRelPose":
            est = belief.objects.get(a.args[0])
            if est is None:
                total += 1.0
                continue
            meas = look_noise(belief, here, est.center)
            n = max(1, looks_needed(est.sigma, float(a.value), meas))
            looks[est.name] = max(looks.get(est.name, 0), n)
        elif p == "BClear":
            region, ex = a.args
            if not isinstance(region, Region) or not isinstance(ex, frozenset):
                total += 1.0
                continue
            eps = float(a.value) if not isinstance(a.value, bool) else belief.params.eps_clear
            k = k_of(eps)
            for name in belief.blockers(region, eps, ex):
                if belief.in_the_way(region, name):
                    drags.add(name)
                    continue
                est = belief.objects[name]
                need = _sigma_to_clear(region, est.box, k)
                meas = look_noise(belief, here, est.center)
                n = max(1, looks_needed(est.sigma, need, meas)) if need > 0 else 1
                looks[name] = max(looks.get(name, 0), n)
            if belief.bumped(region):
                total += 1.0
        elif p == "Observed" and isinstance(a.args[0], Region) and a.value is True:
            # a look from the region's view point: if the subgoal has the robot elsewhere, a detour
            view = a.args[0].view
            total += 1.0 + (0.0 if there is None else max(here.dist(view) + view.dist(there) - here.dist(there), 0.0))
        elif p in ("Placed", "Keep"):
            continue  # an effect only / a reservation that always holds
        else:
            total += 1.0
    return total + DRAG * len(drags) + float(sum(looks.values()))
