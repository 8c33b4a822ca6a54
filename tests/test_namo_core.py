"""NAMO: geometry, belief updates, the world's separation from the belief, scenarios, end-to-end runs."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.acting.metrics import Outcome  # noqa: E402
from nowplan.acting.run import run_episode  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief, along  # noqa: E402
from nowplan.domains.namo.geometry import Box, MapGeometry, Pt, Region, point_back  # noqa: E402
from nowplan.domains.namo.maps import BUILTIN  # noqa: E402
from nowplan.domains.namo.paths import PathPlanner  # noqa: E402
from nowplan.domains.namo.scenarios import SCENARIOS, make  # noqa: E402
from nowplan.domains.namo.spec import parse  # noqa: E402
from nowplan.domains.registry import get_domain  # noqa: E402
from nowplan.errors import ScenarioError  # noqa: E402


def test_box_segment_distance_and_region_overlap():
    box = Box(2.0, 1.0, 0.5, 0.5)
    assert box.distance_to_segment(Pt(0, 1), Pt(4, 1)) == 0.0
    assert box.distance_to_segment(Pt(0, 2), Pt(4, 2)) == pytest.approx(0.75)
    r = Region(Pt(0, 2), Pt(4, 2), 0.3)
    assert not r.hits_box(box)
    assert r.hits_box(box, grow=0.5)


def test_point_back_and_along():
    pts = [Pt(0, 0), Pt(3, 0), Pt(3, 1)]
    assert point_back(pts, 2.0) == Pt(3, 0)  # the last piece is short: its start
    assert point_back([Pt(0, 0), Pt(5, 0)], 2.0) == Pt(3, 0)
    assert along(pts, 3.5) == Pt(3, 0.5)
    assert along(pts, 99) == Pt(3, 1)


def test_visibility_is_blocked_by_walls():
    geom = MapGeometry(4.0, 2.0, ((1.9, 0.0, 2.1, 2.0),))
    g = geom.grid
    left, right = g.cell(Pt(1.0, 1.0)), g.cell(Pt(3.0, 1.0))
    seen = g.visible(Pt(0.5, 1.0), np.array([left, right]), geom.wall_mask, 4.0)
    assert seen.tolist() == [True, False]


def test_path_planner_goes_around_walls_and_prefers_detours_to_clearing():
    geom = MapGeometry(6.0, 4.0, ((2.9, 0.0, 3.1, 2.5),))
    b = NamoBelief(geom, np.array([0.5, 0.5]))
    b.observed[:] = True
    pp = PathPlanner.of(b, foresight=False)
    path = pp.path(Pt(0.5, 0.5), Pt(5.5, 0.5))
    assert path is not None and max(p.y for p in path) > 2.5  # over the wall's end
    for a, c in zip(path, path[1:]):
        assert geom.segment_free(a, c)


def test_kalman_update_shrinks_uncertainty_and_respects_walls():
    geom = MapGeometry(4.0, 2.0, ((0.0, 0.0, 4.0, 0.3),))
    b = NamoBelief(geom, np.array([1.0, 1.0]))
    b.detect("chair", 1.0, -0.6, 0.2, (0.5, 0.5))  # would put the chair into the wall
    est = b.objects["chair"]
    assert est.center.y - 0.25 >= 0.29
    s0 = est.sigma
    b.detect("chair", 1.0, -0.4, 0.05, (0.5, 0.5))
    assert b.objects["chair"].sigma < s0


def test_scenario_errors_name_the_field():
    good = dict(BUILTIN["simple"])
    with pytest.raises(ScenarioError, match=r"objects\[0\]\.size"):
        parse({**good, "objects": [{"name": "a", "at": [1, 1], "size": [0.5, -1]}]})
    with pytest.raises(ScenarioError, match=r"walls\[0\]"):
        parse({**good, "walls": [[1, 1, 0, 2]]})
    with pytest.raises(ScenarioError, match=r"goal"):
        parse({**good, "goal": [99, 1]})
    with pytest.raises(ScenarioError, match=r"params\.segmnt: unknown field"):
        parse({**good, "params": {"segmnt": 1}})
    with pytest.raises(ScenarioError, match=r"objects\[1\]\.name.*twice"):
        parse({**good, "objects": [{"name": "a", "at": [1, 1]}, {"name": "a", "at": [2, 1]}]})


def test_scenario_files_load_by_path(tmp_path):
    p = tmp_path / "mine.json"
    p.write_text(json.dumps(BUILTIN["simple"]))
    ep = get_domain("namo").scenario(str(p))(3)
    assert ep.problem.goal.atoms
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({**BUILTIN["simple"], "sensor": {"range": "far"}}))
    with pytest.raises(ScenarioError, match=r"sensor\.range"):
        get_domain("namo").scenario(str(bad))
    broken = tmp_path / "broken.json"
    broken.write_text("{")
    with pytest.raises(ScenarioError, match="invalid JSON"):
        get_domain("namo").scenario(str(broken))
    binary = tmp_path / "binary.json"
    binary.write_bytes(bytes(range(128, 256)))
    with pytest.raises(ScenarioError, match="not UTF-8 text"):
        get_domain("namo").scenario(str(binary))
    odds = tmp_path / "odds.json"
    odds.write_text(json.dumps({**BUILTIN["simple"], "noise": {"move_fail": 1.5}}))
    with pytest.raises(ScenarioError, match=r"noise\.move_fail: a probability must be in \[0, 1\]"):
        get_domain("namo").scenario(str(odds))


def test_unknown_scenario_lists_the_valid_ones():
    with pytest.raises(ScenarioError, match="valid scenarios: .*corridor"):
        get_domain("namo").scenario("nope")


def test_world_and_belief_are_separate():
    ep = make("simple", 0)
    assert ep.belief.objects == {}  # obstacles are unknown at the start
    assert "box" in ep.world.objects
    assert not ep.belief.observed.all()  # fog


@pytest.mark.parametrize("scenario", ["simple", "corridor"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_hpn_reaches_the_goal(scenario, seed):
    ep = make(scenario, seed)
    m = run_episode(ep, parse_strategy("hpn", max_actions=80), seed=seed)
    assert m.outcome is Outcome.REACHED, m.reason
    goal = next(iter(ep.problem.goal.atoms)).args[0]
    assert ep.world.pose.dist(goal) < 0.35  # the true robot, not just the belief
    assert m.action_counts["Move"] >= 3


def test_corridor_obstacle_must_be_moved():
    ep = make("corridor", 0)
    m = run_episode(ep, parse_strategy("hpn", max_actions=80), seed=0)
    assert m.outcome is Outcome.REACHED
    assert m.action_counts["Pick"] >= 1 and m.action_counts["Place"] >= 1
    box = ep.world.objects["box"]
    hallway = Region(Pt(2.0, 1.5), Pt(6.0, 1.5), 0.25)
    assert not hallway.hits_box(box)  # it was dragged out of the hallway


def test_registered_scenarios_all_build():
    for name in SCENARIOS:
        spec = SCENARIOS.spec(name)
        assert spec.name == name and math.isfinite(spec.size[0])
        ep = make(name, 0)
        start = ep.belief.pose
        assert not ep.belief.geom.robot_blocked[ep.belief.geom.grid.cell(start)]
