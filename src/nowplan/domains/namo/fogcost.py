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

The expected clearance cost of one metre of fog is then
``lam * w * clear_cost``, charged by :mod:`.paths` on top of the length for
every metre that a path runs through fog, so paths compare known obstacles
with unknown ones in the same currency.  With ``fog_pricing`` off, fog is
free (the behaviour before; kept for ablations).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from nowplan.domains.namo.belief import NamoBelief


@dataclass(frozen=True)
class FogPrice:
    """The belief's expected cost of travelling through fog, and what it is made of."""

    density: float  # posterior mean number of objects per m^2 of free space
    width: float  # width of the band (m) in which an object meets a path's centre line
    per_metre: float  # expected clearance cost per metre of fog travelled (path-cost units)
    objects: int  # known objects whose surfaces lie in observed space
    area: float  # observed free area (m^2)


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
    out = FogPrice(density, width, per_metre, len(seen), area)
    c["fog_price"] = out
    return out


def fog_fraction(belief: NamoBelief, cells: np.ndarray) -> float:
    """The fraction of ``cells`` (those a straight segment crosses) that are fog."""
    if cells.size == 0:
        return 0.0
    return float(np.count_nonzero(~belief.observed[cells])) / float(cells.size)
