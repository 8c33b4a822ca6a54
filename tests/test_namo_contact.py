"""A move the world blocks at an object is an observation the belief keeps.

The controller drives from the robot's true pose onto the move's start and
then along it; a robot standing a few centimetres off its (grid-snapped)
start can touch an object on the way back to it although the move itself,
from the start, leads away from the object.  The estimate alone then says
the move is clear, so the same move would be planned again after every
failure (domain 3, seed 6, with exact shadow tests in path smoothing).
After the contact the belief must hold the same move blocked, by that
object, until the object is moved.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.core.operators import Action  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.geometry import Box, MapGeometry, Pt, Region  # noqa: E402
from nowplan.domains.namo.model import build_domain  # noqa: E402
from nowplan.domains.namo.world import NamoWorld, TrueObject  # noqa: E402


def _situation() -> tuple[NamoWorld, NamoBelief, Action, Region]:
    geom = MapGeometry(6.0, 4.0, ())
    pose, start, end = Pt(2.58, 2.0), Pt(2.5, 2.0), Pt(2.92, 2.05)
    box = Box(2.19, 2.43, 0.5, 0.5)  # touches the robot at its pose, deeper at the move's start
    world = NamoWorld(geom, pose, [TrueObject("box", box)], seed=0)
    belief = NamoBelief(geom, np.array([pose.x, pose.y]), robot_sym=start)
    belief._detect("box", box.cx - pose.x, box.cy - pose.y, 0.005, (box.w, box.h))  # well localised
    region = Region(start, end, geom.robot_radius)
    move = build_domain().operator_map["Move"]
    return world, belief, Action(move, (start, end, region)), region


def test_a_move_blocked_by_contact_is_no_longer_clear_in_the_belief() -> None:
    world, belief, action, region = _situation()
    eps = belief.params.eps_clear
    assert belief.at(region.start)
    assert belief.clear(region, frozenset(), eps)  # the estimate alone: the move leads away from the box
    obs = world.execute(action)
    assert not obs.success and obs.info["reason"] == "move blocked by box"
    belief.update(action, obs)
    assert not belief.clear(region, frozenset(), eps)
    assert belief.blockers(region, eps) == ["box"]
    assert belief.in_the_way(region, "box")  # its body, not its shadow: a look will not clear it
    assert belief.clear(region, frozenset({"box"}), eps)  # clearing the box is what makes it clear


def test_the_contact_lapses_where_the_motion_does_not_reach_it_or_the_object_moved() -> None:
    world, belief, action, region = _situation()
    eps = belief.params.eps_clear
    belief.update(action, world.execute(action))
    elsewhere = Region(Pt(3.5, 1.0), Pt(4.5, 1.0), region.radius)  # a move that starts away from here
    assert belief.clear(elsewhere, frozenset(), eps)
    est = belief.objects["box"]
    est.mean = est.mean + np.array([-1.0, 1.0])  # the box was moved away (e.g. picked and placed)
    belief.version += 1
    assert belief.clear(region, frozenset(), eps)
