"""The NAMO goal-distance estimate (nowplan.domains.namo.heuristic) the flat planners search with, the
memoised landmark looks, and the move generator's loop guard (per planning call)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.core.atoms import Goal, atom  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.generators import look_noise, looks_needed  # noqa: E402
from nowplan.domains.namo.geometry import Box, Manip, MapGeometry, Pt, Region  # noqa: E402
from nowplan.domains.namo.heuristic import DRAG, estimate  # noqa: E402
from nowplan.domains.namo.model import DOMAIN  # noqa: E402
from nowplan.domains.namo.scenarios import SCENARIOS, episode  # noqa: E402


def _belief(sigma: float = 0.005) -> NamoBelief:
    geom = MapGeometry(6.0, 4.0, ())
    b = NamoBelief(geom, np.array([1.0, 2.0]), robot_sym=Pt(1.0, 2.0))
    b.observed[:] = True
    b.detect("box", 2.0, 0.0, sigma, (0.4, 0.4))  # at (3, 2)
    return b


def _h(b: NamoBelief, *atoms: object) -> float:
    return estimate(Goal(tuple(atoms)), b, lambda a: DOMAIN.holds(a, b))  # type: ignore[arg-type]


def test_a_goal_that_holds_costs_nothing_and_a_pose_costs_its_distance() -> None:
    b = _belief()
    assert _h(b, atom("RobotAt", Pt(1.0, 2.0)), atom("HandEmpty")) == 0.0
    assert _h(b, atom("RobotAt", Pt(1.0, 3.5))) == pytest.approx(1.5)


def test_an_atom_no_action_achieves_is_a_dead_end() -> None:
    b = _belief()
    m = Manip("box", Pt(1.0, 2.0), Pt(2.5, 2.0), Pt(5.0, 1.0), Pt(4.0, 1.0), Pt(3.5, 1.0), (), (), ())
    assert _h(b, atom("Fits", "box", m)) == math.inf  # planned for where the box is not
    assert _h(b, atom("RobotAt", Pt(2.0, 2.0)), atom("Promising", Pt(1.0, 2.0), "box", value=False)) == math.inf


def test_a_tolerance_costs_the_looks_that_reach_it() -> None:
    b = _belief(sigma=0.2)
    b.sensor = replace(b.sensor, sigma_per_m=0.1)  # 0.21 m at 2 m: several looks
    want = 0.05
    n = looks_needed(b.objects["box"].sigma, want, look_noise(b, b.nominal(), b.objects["box"].center))
    assert n > 1
    assert _h(b, atom("BVRelPose", "box", value=want)) == pytest.approx(n)


def test_an_object_in_the_way_of_several_regions_is_dragged_once() -> None:
    b = _belief()
    a = Region(Pt(1.0, 2.0), Pt(4.5, 2.0), 0.25)
    c = Region(Pt(1.0, 1.9), Pt(4.5, 2.1), 0.25)
    assert b.in_the_way(a, "box") and b.in_the_way(c, "box")
    one = _h(b, atom("BClear", a, frozenset(), value=0.025))
    both = _h(b, atom("BClear", a, frozenset(), value=0.025), atom("BClear", c, frozenset(), value=0.025))
    assert one == both == DRAG
    assert _h(b, atom("BClear", a, frozenset({"box"}), value=0.025)) == 0.0  # excepted: nothing to do


def test_the_belief_offers_it_to_the_online_policy() -> None:
    from nowplan.belief.protocols import HasHeuristic

    ep = episode(SCENARIOS.spec("domain1"), 0)
    assert isinstance(ep.belief, HasHeuristic) and ep.belief.planning_heuristic is estimate


@pytest.mark.parametrize("strategy, used", [("flat", True), ("flat+flexible+serendipity", True), ("hpn", False),
                                            ("hpn+flexible+foresight", False)])
def test_a_flat_strategy_plans_with_it_and_a_hierarchical_one_does_not(strategy: str, used: bool) -> None:
    from nowplan.acting.hpn import Executive
    from nowplan.acting.strategy import parse_strategy

    ep = episode(SCENARIOS.spec("domain1"), 0)
    ex = Executive(ep.problem, ep.world, ep.belief, parse_strategy(strategy))
    assert (ex.context().extras.get("heuristic") is estimate) == used


def test_landmark_looks_are_memoised_per_belief_version() -> None:
    from nowplan.core.atoms import Var
    from nowplan.domains.namo.generators import gen_look_landmark

    geom = MapGeometry(6.0, 4.0, (), landmarks=(("L", Pt(3.0, 3.5)),))
    b = NamoBelief(geom, np.array([1.0, 2.0]), robot_sym=Pt(1.0, 2.0))
    want = {Var("e"): 0.02}
    goal = Goal((atom("Localized", value=0.02),))
    b.robot_var = 0.1**2  # one look (landmark sigma 0.03) cannot reach 0.02 from here
    assert list(gen_look_landmark(want, goal, b, None)) == []
    b.robot_var = 0.025**2
    b.version += 1  # an update: what was memoised for the old belief is not used
    assert [x[Var("lm")] for x in gen_look_landmark(want, goal, b, None)] == ["L"]


def test_the_move_generators_loop_guard_counts_per_planning_call() -> None:
    from nowplan.domains.namo.belief import LOOP_LIMIT

    b = _belief()
    first, second = object(), object()
    assert not any(b.planning_loop(first) for _ in range(LOOP_LIMIT - 1))
    assert b.planning_loop(first)  # this call asked for moves LOOP_LIMIT times: it gives up
    assert not b.planning_loop(second)  # the next call (e.g. the level above replanning) still gets moves
    b.version += 1  # an action: every count starts again
    assert not b.planning_loop(first)
