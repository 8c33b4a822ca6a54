"""Fog priced by its expected clearance cost (fogcost.py) in the path costs and the triggers."""

from __future__ import annotations

import math
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

pytest.importorskip("shapely")

from nowplan.core.levels import LevelMap  # noqa: E402
from nowplan.errors import NowplanError  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.fogcost import fog_price  # noqa: E402
from nowplan.domains.namo.geometry import Grid, MapGeometry, Pt  # noqa: E402
from nowplan.domains.namo.params import Params  # noqa: E402
from nowplan.domains.namo.paths import PathPlanner, dijkstra  # noqa: E402
from nowplan.domains.namo.scenarios import make  # noqa: E402
from nowplan.domains.namo.triggers import make_triggers  # noqa: E402
from nowplan.planning.regression import plan as regression_plan  # noqa: E402


def _belief(params: Params = Params(), walls: tuple[tuple[float, float, float, float], ...] = ()) -> NamoBelief:
    return NamoBelief(MapGeometry(8.0, 4.0, walls), np.array([0.5, 2.0]), params=params)


def _observe_left(b: NamoBelief, x: float) -> float:
    """Observe every cell left of ``x`` (and nothing else); returns the free area observed (m^2)."""
    g = b.geom.grid
    b.observed[:] = g.xs < x
    b._bump()
    return float(np.count_nonzero(b.observed & ~b.geom.wall_mask)) * g.res * g.res


def test_density_is_the_gamma_poisson_posterior_mean_of_what_was_observed():
    p = Params(fog_prior_objects=1.0, fog_prior_area=10.0)
    b = _belief(p)
    area = _observe_left(b, 4.0)
    f = fog_price(b)
    assert f.objects == 0 and f.area == pytest.approx(area)
    assert f.density == pytest.approx(1.0 / (10.0 + area))
    assert f.width == pytest.approx(2 * b.geom.robot_radius + p.fog_prior_width)
    assert f.per_metre == pytest.approx(f.density * f.width * p.clear_cost)
    b._detect("seen", 2.0, 0.0, 0.01, (0.4, 0.6))  # in observed space, 2 m ahead
    b._detect("far", 6.5, 1.0, 0.01, (0.4, 0.4))  # in fog (a prior map entry, say): not evidence
    f2 = fog_price(b)
    assert f2.objects == 1
    assert f2.density == pytest.approx(2.0 / (10.0 + area))
    assert f2.width == pytest.approx(2 * b.geom.robot_radius + 0.5)  # the seen object's mean width
    assert f2.per_metre > f.per_metre


def test_more_observed_space_without_objects_lowers_the_price():
    b = _belief()
    _observe_left(b, 2.0)
    small = fog_price(b).per_metre
    _observe_left(b, 6.0)
    assert fog_price(b).per_metre < small


def test_pricing_off_makes_fog_free():
    b = _belief(Params(fog_pricing=False))
    _observe_left(b, 1.0)
    assert fog_price(b).per_metre == 0.0
    pp = PathPlanner.of(b, False)
    a, c = Pt(2.0, 2.0), Pt(5.0, 2.0)
    assert pp.segment_cost(a, c) == pytest.approx(a.dist(c))


def test_a_straight_move_pays_the_fog_price_for_the_part_it_runs_in_fog():
    b = _belief(Params(fog_prior_objects=3.0))
    _observe_left(b, 4.0)
    rho = fog_price(b).per_metre
    assert rho > 0
    pp = PathPlanner.of(b, False)
    seen_a, seen_b = Pt(0.5, 2.0), Pt(3.5, 2.0)
    fog_a, fog_b = Pt(4.5, 2.0), Pt(7.5, 2.0)
    assert pp.segment_cost(seen_a, seen_b) == pytest.approx(3.0)
    assert pp.segment_cost(fog_a, fog_b) == pytest.approx(3.0 * (1.0 + rho))
    half = pp.segment_cost(Pt(2.0, 2.0), Pt(6.0, 2.0))  # half of it in fog
    assert 4.0 + 1.5 * rho < half < 4.0 + 2.5 * rho


def test_dijkstra_scales_edges_by_their_cells_per_metre_cost():
    g = Grid(2.0, 1.0, 0.2)
    free = np.ones(g.n, dtype=bool)
    dist0, _ = dijkstra(g, free, 0)
    dist1, _ = dijkstra(g, free, 0, per_metre=np.full(g.n, 0.5))
    far = g.n - 1
    assert dist1[far] == pytest.approx(1.5 * dist0[far])
    dist2, _ = dijkstra(g, free, 0, per_metre=np.zeros(g.n))
    assert dist2 == dist0


def test_the_path_planner_leaves_a_short_foggy_way_for_an_observed_one_when_fog_is_dear():
    # a block in the middle; the way above it is shorter but unobserved, the way below observed
    walls = ((2.5, 1.2, 5.5, 2.9),)
    start, goal = Pt(0.5, 3.1), Pt(7.5, 3.1)

    def route(params: Params) -> list[Pt]:
        b = NamoBelief(MapGeometry(8.0, 4.0, walls), np.array([start.x, start.y]), params=params)
        g = b.geom.grid
        b.observed[:] = (g.ys < 2.0) | (g.xs < 2.0) | (g.xs > 6.0)
        b._bump()
        path = PathPlanner.of(b, False).path(start, goal)
        assert path is not None
        return path

    free_fog = route(Params(fog_pricing=False))
    assert min(p.y for p in free_fog) > 2.9  # over the block: shorter, through fog
    dear = route(Params(fog_prior_objects=20.0))  # fog expected to be full of objects
    assert min(p.y for p in dear) < 1.2  # under the block, through observed space
    length = sum(a.dist(c) for a, c in zip(dear, dear[1:]))
    assert length > sum(a.dist(c) for a, c in zip(free_fog, free_fog[1:]))


def _fig6_with_crate(params: Params) -> tuple[object, NamoBelief]:
    ep = make("fig6", 0)
    b = ep.belief
    dom = ep.problem.domain
    res = regression_plan(dom, {}, b, ep.problem.goal, LevelMap(dom.top_level))
    assert res.solved and res.plan is not None
    plan = res.plan
    route = [a.args[2] for a in plan.actions if a.name == "Move"]
    mid = route[len(route) // 2].centroid
    # the straight route's band has been looked at (up to the crate); the sides of the room are fog
    g = b.geom.grid
    b.observed[:] = (np.abs(g.ys - mid.y) < 0.45) & (g.xs < mid.x + 0.3)
    b._detect("crate", mid.x - b.pose.x, mid.y - b.pose.y, 0.02, (0.6, 0.6))
    b._detect("seen1", 1.5 - b.pose.x, 0.0, 0.02, (0.3, 0.3))  # objects seen so far (evidence of clutter)
    b.params = params
    b._bump(percept=True)
    return plan, b


def test_a_detour_through_fog_replans_only_if_it_pays_in_expectation():
    """Stage 2 compares the old route (clearing the crate) with a detour through fog, both priced."""
    plan, b = _fig6_with_crate(Params(fog_pricing=False))
    new_obstacle, _ = make_triggers(b.params)
    reason = new_obstacle(plan, b)  # fog free: the detour looks clearly cheaper
    assert reason is not None and "shorter" in reason

    plan, b = _fig6_with_crate(Params(fog_prior_objects=8.0, fog_prior_area=10.0))
    rho = fog_price(b).per_metre
    assert rho > 2.0  # a cluttered prior: each metre of fog is expected to cost more than 2 m
    new_obstacle, _ = make_triggers(b.params)
    assert new_obstacle(plan, b) is None  # the detour's fog is dearer than clearing the crate


def test_fig6_detour_still_happens_with_the_default_price():
    """Fig. 6: a box on the straight path through a foggy room; the detour beside it is worth it."""
    plan, b = _fig6_with_crate(Params())
    rho = fog_price(b).per_metre
    assert 0 < rho < 2.0 and math.isfinite(rho)
    new_obstacle, _ = make_triggers(b.params)
    reason = new_obstacle(plan, b)
    assert reason is not None and "shorter" in reason


def test_params_from_a_scenario_file_turn_pricing_off():
    from nowplan.domains.namo.spec import parse

    spec = parse({"name": "x", "size": [4, 3], "start": [0.5, 1.5], "goal": [3.5, 1.5],
                           "params": {"fog_pricing": False, "fog_prior_area": 5.0}})
    assert spec.params.fog_pricing is False and spec.params.fog_prior_area == 5.0
    with pytest.raises(NowplanError, match="fog_prior_area"):
        parse({"name": "x", "size": [4, 3], "start": [0.5, 1.5], "goal": [3.5, 1.5],
               "params": {"fog_prior_area": "lots"}})


@pytest.mark.timeout(120, method="thread")
@settings(max_examples=40, deadline=None, suppress_health_check=list(HealthCheck))
@given(
    seen_x=st.floats(0.5, 7.5),
    objects=st.integers(0, 4),
    ax=st.floats(0.4, 7.6), ay=st.floats(0.4, 3.6), bx=st.floats(0.4, 7.6), by=st.floats(0.4, 3.6),
)
def test_fog_price_bounds_every_move_and_every_tree(seen_x, objects, ax, ay, bx, by):
    """A move costs its length, plus at most the fog price per metre, never less; trees likewise."""
    b = _belief()
    _observe_left(b, seen_x)
    for i in range(objects):  # objects seen in the observed part (out of the way: at the map's bottom edge)
        b._detect(f"o{i}", min(seen_x, 0.6 + 0.5 * i) - b.pose.x, 0.3 - b.pose.y, 0.01, (0.2, 0.2))
    rho = fog_price(b).per_metre
    assert rho == pytest.approx(fog_price(b).density * fog_price(b).width * b.params.clear_cost)
    a, c = Pt(ax, ay), Pt(bx, by)
    pp = PathPlanner.of(b, False)
    free = PathPlanner.of(_with_free_fog(b), False)
    cost, length = pp.segment_cost(a, c), a.dist(c)
    if free.segment_cost(a, c) == pytest.approx(length):  # (no object in the way)
        assert length - 1e-9 <= cost <= length * (1 + rho) + 1e-9
    g = b.geom.grid
    priced, _ = pp.tree(a)
    unpriced, _ = free.tree(a)
    k = g.cell(c)
    if math.isfinite(unpriced[k]):
        assert unpriced[k] - 1e-9 <= priced[k] <= unpriced[k] * (1 + rho) + 1e-9


def _with_free_fog(b: NamoBelief) -> NamoBelief:
    import copy

    free = copy.deepcopy(b)
    free.params = Params(fog_pricing=False)
    free._bump()
    return free
