"""What crossing fog is expected to cost, under the belief: unknown space is not free.

The robot knows the walls, not the movable objects; space it has not seen
(*fog*) may hold objects it will have to clear.  Planning as if fog were
free makes a route through unseen space look cheaper than a route past an
object already seen, although the unseen route is expected to meet objects
too (seed 000, domain 2: a foggy side corridor).  This module prices fog by
its expected clearance cost, computed from the belief alone:

* objects lie in free space as a Poisson process of unknown density
  ``lam`` (objects per m^2) with a Gamma prior of ``fog_prior_objects``
  objects in ``fog_prior_area`` m^2; the robot has observed an area ``A`` of
  free space and knows ``n`` objects whose surfaces it has seen there, so the
  posterior mean density is ``(fog_prior_objects + n) / (fog_prior_area + A)``
  (the conjugate Gamma-Poisson update);
* a path meets an object when the object's centre lies within
  ``robot_radius + object half-width`` of the robot's centre line: per
  metre travelled through fog it sweeps a band of width
  ``w = 2 * robot_radius + mean object width`` (the mean over the objects
  detected so far, the prior's ``fog_prior_width`` before any), so it meets
  ``lam * w`` objects per metre in expectation;
* an object met costs what the path planner charges for a known one in the
  way, ``clear_cost``.

* an object met costs what the path planner charges for a known one in the
  way, ``clear_cost``, where the robot cannot pass beside it; where free
  space is wide enough it steps around it instead, for the extra length of
  the side-step (``bypass_cost``).  Where a path runs through free space of
  width ``W`` (:attr:`MapGeometry.passage_width`), an object of width ``s``
  met at a uniformly random lateral place leaves a gap of at least the
  robot's diameter plus ``pass_margin`` on one side in the fraction
  ``f = min(1, 2 (W - s - 2r - margin) / (W - s))`` of the places (0 in a
  corridor one object fills, 1 in a room), so it is expected to cost
  ``(1 - f) clear_cost + f bypass_cost`` there.

The expected clearance cost of one metre of fog at a cell is then
``lam * w * object_cost``: ``lam * w * clear_cost`` (``FogPrice.per_metre``)
in passages an object blocks, much less in rooms.  :mod:`.paths` charges it
on top of the length for every metre that a path runs through fog, so paths
compare known obstacles with unknown ones in the same currency.  With
``fog_pricing`` off, fog is free (the behaviour before; kept for ablations).

The count of objects a route meets in fog is random (Poisson given the
density), so the difference between two routes' fog costs has a spread
(:func:`fog_cost_spread`); selective replanning's path trigger asks a gain
to stand out of it (:mod:`.triggers`).
"""

from __future__ import annotations

from collections.abc import Sequence
import logging
import math
from dataclasses import dataclass

import numpy as np

from nowplan.domains.namo.belief import NamoBelief
from nowplan.domains.namo.geometry import Pt

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class FogPrice:
    """The belief's expected cost of travelling through fog, and what it is made of."""

    density: float  # posterior mean number of objects per m^2 of free space
    width: float  # width of the band (m) in which an object meets a path's centre line
    per_metre: float  # expected clearance cost per metre of fog where an object blocks the way
    objects: int  # known objects whose surfaces lie in observed space
    area: float  # observed free area (m^2)
    object_cost: np.ndarray  # per cell: the expected cost of an object met there (clearing or side-step)

    @property
    def cells(self) -> np.ndarray:
        """Per cell: the expected clearance cost per metre of fog there (0 with pricing off)."""
        if self.per_metre <= 0:
            return np.zeros_like(self.object_cost)
        return self.density * self.width * self.object_cost


def bypass_cost(width: float) -> float:
    """The extra length of stepping around an object met in open space.

    The object's centre lies within ``width / 2`` of the path's centre line,
    so the path moves aside by at most ``width / 2``; doing so over a
    distance ``width`` before and after it lengthens the path by
    ``2 (hypot(width, width / 2) - width)`` (about 0.24 m for a 1 m band).
    """
    return 2.0 * (math.hypot(width, width / 2.0) - width)


def object_cost(belief: NamoBelief, size: float, width: float) -> np.ndarray:
    """Per cell: the expected cost of an object of ``size`` met by a path through that cell."""
    p = belief.params
    geom = belief.geom
    free_w = geom.passage_width
    need = 2.0 * geom.robot_radius + p.pass_margin
    span = np.maximum(free_w - size, 1e-9)
    f = np.clip(2.0 * (free_w - size - need) / span, 0.0, 1.0)
    return (1.0 - f) * p.clear_cost + f * min(bypass_cost(width), p.clear_cost)


def fog_price(belief: NamoBelief) -> FogPrice:
    """The expected clearance cost per metre of fog in this belief (cached per belief version)."""
    c = belief.cache()
    hit = c.get("fog_price")
    if isinstance(hit, FogPrice):
        return hit
    p = belief.params
    geom = belief.geom
    g = geom.grid
    free_seen = belief.observed & ~geom.wall_mask
    area = float(np.count_nonzero(free_seen)) * g.res * g.res
    # an object counts where the robot has seen its surface: its box, grown by a cell, meets observed
    # space (its own cells stay fog: the sensor sees an object's surface, not behind it)
    seen = [o for o in belief.objects.values() if bool(free_seen[g.box_mask(o.box, g.res)].any())]
    density = (p.fog_prior_objects + len(seen)) / (p.fog_prior_area + area)
    size = (sum((o.size[0] + o.size[1]) / 2 for o in seen) / len(seen)) if seen else p.fog_prior_width
    width = 2 * geom.robot_radius + size
    per_metre = density * width * p.clear_cost if p.fog_pricing else 0.0
    out = FogPrice(density, width, per_metre, len(seen), area, object_cost(belief, size, width))
    c["fog_price"] = out
    return out


def fog_along(per_metre: np.ndarray, cells: np.ndarray) -> float:
    """The mean per-metre fog cost over ``cells`` (those a straight segment crosses, sampled evenly)."""
    if cells.size == 0:
        return 0.0
    return float(np.mean(per_metre[cells]))


def _band(belief: NamoBelief, segments: Sequence[tuple[Pt, Pt]], half_width: float, size: float) -> np.ndarray:
    """The fog cells within ``half_width`` of a route's centre line where an object's centre fits."""
    g = belief.geom.grid
    band = np.zeros(g.n, dtype=bool)
    for a, b in segments:
        band |= g.capsule_mask(a, b, half_width)
    return np.asarray(band & ~belief.observed & (belief.geom.wall_distance >= size / 2), dtype=bool)


def fog_cost_spread(
    belief: NamoBelief, new: Sequence[tuple[Pt, Pt]], old: Sequence[tuple[Pt, Pt]],
) -> float:
    """The standard deviation of the fog cost that route ``new`` runs into and route ``old`` does not.

    A route meets the objects in the fog band it sweeps (its centre line
    grown by half the band width ``w``, where an object's centre fits); one
    met at cell ``c`` costs ``k(c)`` (:func:`object_cost`).  Objects in fog
    both bands share cost both routes the same.  The new route's exclusive
    part ``E`` holds a Poisson number of objects given the density ``lam``,
    so its cost has variance ``lam * sum(k(c)^2 * a)`` over ``E`` (``a`` a
    cell's area); the density's own uncertainty (its Gamma posterior,
    variance ``(a0 + n) / (b0 + A)^2``) adds ``Var[lam] * sum(k(c) * a)^2``.
    A detour into a long foggy corridor, where every object met must be
    cleared, is uncertain; one through open rooms, where objects met are
    side-stepped, hardly is.  Zero when fog is free (``fog_pricing`` off)
    or the new route sweeps no fog the old one does not.
    """
    p = belief.params
    if not p.fog_pricing:
        return 0.0
    price = fog_price(belief)
    a = belief.geom.grid.res ** 2
    size = price.width - 2 * belief.geom.robot_radius
    bn, bo = _band(belief, new, price.width / 2, size), _band(belief, old, price.width / 2, size)
    k = price.object_cost[bn & ~bo]
    var_lam = (p.fog_prior_objects + price.objects) / (p.fog_prior_area + price.area) ** 2
    within = price.density * a * float(np.sum(k**2))
    between = var_lam * (a * float(np.sum(k))) ** 2
    log.debug(
        "fog spread: %.1f m^2 of fog only on the new route, expected cost %.2f, sd %.2f (%.2f from the density)",
        a * k.size, price.density * a * float(np.sum(k)), math.sqrt(within + between), math.sqrt(between),
    )
    return math.sqrt(within + between)
