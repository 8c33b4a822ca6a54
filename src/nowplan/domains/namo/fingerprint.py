"""A NAMO belief's fingerprint: which situation the agent is in, for the progress guard.

The progress guard (:mod:`nowplan.acting.progress`) calls a return to a situation
seen before, by the agent's own successful actions, a cycle.  The fingerprint must
be coarse enough that a real cycle repeats it, and fine enough that progress
changes it:

* the robot's mean pose to ``FP_POS`` metres and its standard deviation to a factor
  ``FP_SIGMA`` (a log scale: a look at a landmark tightens it by more than that;
  the jitter at the end of a move does not shift a pose that far);
* each known object lying in the world, the same way; what the robot holds;
* how many cells are observed (fog only clears: any revealed cell is progress);
* the cells where the robot bumped into something unseen, and the points a contact
  with an object stopped it from reaching;
* the lessons that steer the planner *now*: objects found unmovable and looks found
  futile since the last perceptual event.

Left out: counters (``version``, ``percept`` — a place always bumps ``percept``,
and a drag that ends where it started is no progress), the trajectory and the
planner's memos.
"""

from __future__ import annotations

import math
from collections.abc import Hashable
from typing import TYPE_CHECKING

import numpy as np

from nowplan.domains.namo.geometry import Pt

if TYPE_CHECKING:
    from nowplan.domains.namo.belief import NamoBelief

FP_POS = 0.1  # metres
FP_SIGMA = 1.25  # ratio of standard deviations


def q_pt(p: Pt) -> tuple[int, int]:
    """A position's bin (``FP_POS`` metres square)."""
    return round(p.x / FP_POS), round(p.y / FP_POS)


def q_sigma(s: float) -> int:
    """A standard deviation's bin on a log scale (``FP_SIGMA`` apart); 1 mm and below share one."""
    return round(math.log(max(s, 1e-3)) / math.log(FP_SIGMA))


def fingerprint(b: NamoBelief) -> Hashable:
    """The belief's situation (equal for beliefs the progress guard treats as the same)."""
    return (
        q_pt(b.pose), q_sigma(b.robot_sigma), b.held,
        tuple((o.name, q_pt(o.center), q_sigma(o.sigma)) for o in b.free_objects()),
        int(np.count_nonzero(b.observed)),
        frozenset(b.bumps),
        frozenset(b.drag_margin.items()),
        frozenset((n, q_pt(h)) for n, hits in sorted(b.touched.items()) for h, _ in hits),
        frozenset(n for n in b.unmovable if b.stuck(n)),
        frozenset(k for k, v in b.futile_looks.items() if v == b.percept),
        b.misses_now(),
        frozenset(b.blocked_picks),
    )
