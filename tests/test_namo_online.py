"""NAMO under the online policy (replanning after every action, seed 004 Alg. 1).

A plan made right after a grasp routes its moves without knowing where the
held object was meant to go (the placement was chosen by the plan that
picked it, for that plan's moves).  Putting it down there may block the
new plan's way: the placement generator then places it elsewhere from where
the robot stands, out of every region the goal needs clear, instead of
offering only the committed placement (domain 1, seeds 2 and 8, no faults:
"no plan for the goal" right after a Pick).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.core.atoms import Goal, Var, atom  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.geometry import Box, Manip, MapGeometry, Pt, Region  # noqa: E402
from nowplan.domains.namo.placement import gen_place  # noqa: E402

R, EX, M = Var("r"), Var("ex"), Var("m")


def _holding(place: Pt) -> tuple[NamoBelief, Manip]:
    """The robot at (2, 2) holds a 0.4 m box 0.5 m north of it, planned to go to ``place``."""
    geom = MapGeometry(6.0, 4.0, ())
    home = Pt(2.0, 2.0)
    box = Box(2.0, 2.5, 0.4, 0.4)
    belief = NamoBelief(geom, np.array([home.x, home.y]), robot_sym=home)
    belief.observed[:] = True
    belief.detect("box", 0.0, 0.5, 0.005, (box.w, box.h))
    release = Pt(place.x, place.y - 0.5)
    m = Manip("box", home, home, box.center, place, release, (home,), (home, release), (release, home),
              Region(home, home, 0.0))
    belief.held, belief.held_manip, belief.grip = "box", m, (np.array([0.0, 0.5]), np.eye(2) * 1e-4)
    return belief, m


def _placements(belief: NamoBelief, goal: Goal, cleared: Region | None) -> list[Manip]:
    bindings = {} if cleared is None else {R: cleared, EX: frozenset()}
    return [b[M] for b in gen_place(bindings, goal, belief, None)]


@pytest.mark.parametrize("only_hand", [True, False])
def test_a_held_object_is_placed_out_of_the_regions_the_goal_needs_clear(only_hand: bool) -> None:
    belief, m = _holding(Pt(3.0, 2.5))
    way = Region(Pt(2.0, 2.0), Pt(4.5, 2.3), 0.25)  # the new plan's move: through the planned spot
    assert way.hits_box(Box(3.0, 2.5, 0.4, 0.4))
    goal = Goal((atom("RobotAt", m.home), atom("BClear", way, frozenset(), value=0.025)))
    cleared = None if only_hand else Region(Pt(2.0, 2.0), Pt(2.0, 1.0), 0.25)
    opts = _placements(belief, goal, cleared)
    assert opts, "no placement offered: the plan after the grasp has no way to put the object down"
    for o in opts:
        assert not way.hits_box(Box(o.place.x, o.place.y, 0.4, 0.4)), o
        assert o.home == m.home and o.pick_conf == m.pick_conf  # still held as grasped (Holding holds)


def test_the_planned_placement_is_kept_while_the_goal_leaves_it_free() -> None:
    belief, m = _holding(Pt(3.0, 2.5))
    way = Region(Pt(2.0, 2.0), Pt(2.0, 0.5), 0.25)  # the other way: the planned spot stays free
    goal = Goal((atom("RobotAt", m.home), atom("BClear", way, frozenset(), value=0.025)))
    assert _placements(belief, goal, None)[0] == m


@pytest.mark.slow
# online seed 8 ended "no plan for the goal" after its pick at 2771927; with fog priced by passage
# (issue 17) seed 2 no longer picks, so online+reuse runs seed 1, which does
@pytest.mark.parametrize("strategy, seed", [("online", 8), ("online+reuse", 1)])
def test_the_online_policy_reaches_the_goal_after_a_pick(strategy: str, seed: int) -> None:
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import get_domain

    spec = get_domain("namo")
    st = parse_strategy(strategy, base_planner=spec.planner, time_limit=120.0)
    m = run_episode(spec.scenario("domain1")(seed), st, seed)
    assert m.outcome.value == "reached", m.reason
    assert m.action_counts["Pick"] >= 1  # the scenario does need a pick (else the test shows nothing)


@pytest.mark.slow
def test_hpn_replans_above_a_refinement_whose_search_gave_up() -> None:
    # domain 1, sensor noise 0.1 m/m, seed 6: refining one move asked for moves 1500 times and gave
    # up; the guard then counted per belief, so the top level's replanning got no move at all and the
    # run ended "no plan for the goal"; counted per planning call, the top level routes around
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import Faults, apply_faults

    spec = get_domain("namo")
    st = parse_strategy("hpn", base_planner=spec.planner, time_limit=240.0)
    ep = spec.scenario("domain1")(6)
    apply_faults(ep, Faults(sigma_per_m=0.1))
    m = run_episode(ep, st, 6)
    assert m.outcome.value == "reached", m.reason


# -- a missed detection while holding (issue 14: domain 1, misses 0.3, online seeds 6 and 14) ---------------
def _holding_close(other_at: Pt | None) -> tuple[NamoBelief, Manip]:
    """As :func:`_holding`, but the robot drove to the pick configuration from a home 0.6 m west, the
    grasp left the box touching the robot's clearance (0.45 m north of it), and optionally another
    0.4 m box, localised to 5 cm, lies at ``other_at``."""
    belief, m = _holding(Pt(3.0, 2.5))
    home = Pt(1.4, 2.0)
    m = replace(m, home=home, pick_path=(home, m.pick_conf), return_path=(m.release, home))
    belief.held_manip = m
    belief.objects["box"].mean = np.array([2.0, 2.45])
    belief.grip = (np.array([0.0, 0.45]), np.eye(2) * 1e-4)
    if other_at is not None:
        belief.detect("other", other_at.x - 2.0, other_at.y - 2.0, 0.05, (0.4, 0.4))
    return belief, m


@pytest.mark.parametrize("other_at", [None, Pt(2.5, 1.75)])
def test_a_held_object_is_re_placed_from_where_the_robot_stands(other_at: Pt | None) -> None:
    # the re-placement of a held object searched a pick path to where the robot stands, which the
    # search keeps out of the object's own clearance and other objects' shadows: with the robot
    # inside either (a grasp leaves the object close; an object a look missed turns up beside the
    # robot) every option was dropped and the run ended "no plan for the goal" right after the pick
    belief, m = _holding_close(other_at)
    if other_at is not None:
        assert belief.blockers(Region(m.pick_conf, m.pick_conf, 0.25), 0.025), "the robot should stand in its shadow"
    way = Region(Pt(2.0, 2.0), Pt(4.5, 2.3), 0.25)  # through the planned spot: it must go elsewhere
    goal = Goal((atom("RobotAt", m.home), atom("BClear", way, frozenset(), value=0.025)))
    opts = _placements(belief, goal, Region(Pt(2.0, 2.0), Pt(2.0, 1.0), 0.25))
    held = [o for o in opts if o.obj == "box"]
    assert held, "no re-placement offered for the held object"
    for o in held:
        assert not way.hits_box(Box(o.place.x, o.place.y, 0.4, 0.4)), o
        assert o.pick_conf == m.pick_conf and o.pick_path == (m.pick_conf,)  # picked already: no pick path


def test_while_holding_an_object_another_one_in_the_way_can_be_moved() -> None:
    # the placement generator offered only the held object while one was held, so a plan made after
    # a grasp could never move a second object (one a missed detection showed only after the grasp)
    belief, m = _holding(Pt(2.0, 3.2))
    belief.detect("other", 1.5, 0.0, 0.01, (0.4, 0.4))  # at (3.5, 2): in the way east
    way = Region(Pt(2.0, 2.0), Pt(4.5, 2.0), 0.25)
    assert belief.blockers(way, 0.025) == ["other"]
    goal = Goal((atom("RobotAt", m.home),))
    moved = {o.obj: o for o in _placements(belief, goal, way)}
    assert "other" in moved, "only the held object was offered"
    o = moved["other"]
    assert o.home == m.home and not way.hits_box(Box(o.place.x, o.place.y, 0.4, 0.4))


@pytest.mark.parametrize("seed", [6, 14])
@pytest.mark.parametrize("strategy", ["online", "online+reuse"])
def test_the_online_policy_recovers_from_an_object_a_look_missed(strategy: str, seed: int) -> None:
    # domain 1, misses 0.3: seed 6 picks an object and only then sees another (missed twice before)
    # beside the robot; seed 14 runs into one it missed, picks it, and stands off the pick
    # configuration.  Both ended "no plan for the goal" (search space exhausted) right after the pick.
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import Faults, apply_faults

    spec = get_domain("namo")
    st = parse_strategy(strategy, base_planner=spec.planner, time_limit=120.0)
    ep = spec.scenario("domain1")(seed)
    apply_faults(ep, Faults(miss=0.3))
    m = run_episode(ep, st, seed)
    assert m.outcome.value == "reached", m.reason
    assert m.action_counts["Pick"] >= 1  # the runs do pick (else the test shows nothing)


def test_a_move_stopped_in_a_doorway_leaves_a_pose_the_planner_can_start_from() -> None:
    # domain 1, failures 0.5, online seed 12: a move stopped in the lower doorway at (4.82, 1.8); the
    # nominal pose, the centre of its 0.2 m cell, (4.9, 1.9), lies within the robot's radius of the
    # wall's end, so no path started there and the run ended "no plan for the goal"
    from nowplan.domains.namo.geometry import snap_free

    geom = MapGeometry(10.0, 6.0, ((4.95, 2.1, 5.05, 3.9),), res=0.2)
    p = Pt(4.82, 1.8)
    assert geom.robot_blocked[geom.grid.cell(geom.grid.snap(p))]
    q = snap_free(geom, p, 0.15)
    assert not geom.robot_blocked[geom.grid.cell(q)] and q.dist(p) <= 0.15
    assert snap_free(geom, Pt(2.0, 2.0), 0.15) == geom.grid.snap(Pt(2.0, 2.0))  # a free cell: its centre
    belief = NamoBelief(geom, np.array([p.x, p.y]), robot_sym=Pt(-1.0, -1.0))
    assert belief.nominal() == q


@pytest.mark.parametrize("strategy", ["online", "online+reuse"])
def test_the_online_policy_goes_on_after_a_move_stopped_in_a_doorway(strategy: str) -> None:
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import Faults, apply_faults

    spec = get_domain("namo")
    st = parse_strategy(strategy, base_planner=spec.planner, time_limit=120.0)
    ep = spec.scenario("domain1")(12)
    apply_faults(ep, Faults(failure=0.5))
    m = run_episode(ep, st, 12)
    assert m.outcome.value == "reached", m.reason
