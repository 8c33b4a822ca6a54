"""A NAMO look that misses its object is futile only when a miss is no longer chance (issue 14 stress runs)."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.acting.metrics import Outcome  # noqa: E402
from nowplan.acting.run import run_episode  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.core.operators import Action  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.geometry import MapGeometry, Pt  # noqa: E402
from nowplan.domains.namo.model import build_domain  # noqa: E402
from nowplan.domains.namo.params import DEFAULT_SENSOR  # noqa: E402
from nowplan.domains.namo.sensing import looks_to_give_up  # noqa: E402
from nowplan.domains.registry import get_domain  # noqa: E402
from nowplan.experiments.faults import apply_faults, split_scenario  # noqa: E402
from nowplan.worlds.base import Observation  # noqa: E402

GEOM = MapGeometry(6.0, 4.0, ())
VIEW = Pt(1.0, 2.0)


def _belief(miss_prob: float) -> NamoBelief:
    b = NamoBelief(GEOM, np.array([VIEW.x, VIEW.y]), sensor=replace(DEFAULT_SENSOR, miss_prob=miss_prob))
    b.detect("box", 3.0, 0.0, 0.3, (0.5, 0.5))
    return b


def _look_and_miss(b: NamoBelief) -> None:
    op = build_domain().operator_map["LookObj"]
    b.update(Action(op, (VIEW, "box", None, None, None, 1)), Observation(True, {"detections": []}))


def test_the_looks_to_give_up_on_grow_with_the_sensors_miss_rate():
    assert looks_to_give_up(0.0) == looks_to_give_up(0.1) == 1  # a sensor that (nearly) never misses
    assert looks_to_give_up(0.3) == 2 and looks_to_give_up(0.5) == 4  # 0.3**2, 0.5**4 <= 0.1
    ks = [looks_to_give_up(m / 20) for m in range(21)]
    assert ks == sorted(ks) and max(ks) < 1000  # monotone and bounded even at miss_prob 1


@pytest.mark.parametrize("miss, looks", [(0.0, 1), (0.3, 2), (0.5, 4)])
def test_a_look_that_missed_is_futile_after_as_many_misses_as_chance_allows(miss, looks):
    b = _belief(miss)
    seen = {b.fingerprint()}
    for i in range(1, looks + 1):
        _look_and_miss(b)
        futile = b.futile_looks.get((VIEW, "box")) == b.percept
        assert futile == (i == looks)
        assert b.fingerprint() not in seen  # each miss is news: the progress guard sees no cycle
        seen.add(b.fingerprint())


@pytest.mark.slow
def test_a_missed_look_does_not_bar_the_only_view_of_an_object():
    # NAMO domain1 at failure 0.5, sensor noise 0.1/m and misses 0.3, flat+flexible+serendipity, seed 4:
    # one miss of right0 from (8.7, 4.7) marked every look from there futile and the next planner call
    # found no plan ("search space exhausted") after 23 actions
    base, faults = split_scenario("domain1?failure=0.5&sigma_per_m=0.1&miss=0.3")
    ep = get_domain("namo").scenario(base)(4)
    apply_faults(ep, faults)
    m = run_episode(ep, parse_strategy("flat+flexible+serendipity", time_limit=60.0), seed=4)
    assert m.outcome is Outcome.REACHED, m.reason


def test_a_move_whose_blocker_was_not_found_from_its_start_is_offered_from_halfway():
    """An object whose shadow (not its body) lies in a move's way, and which a look from the move's
    start failed to find (occluded from there), is looked for from elsewhere: the move is offered in
    two, from a point halfway (sensor noise 0.2/m, seed 12: the look was repeated from the start,
    then no plan)."""
    from nowplan.core.atoms import Goal
    from nowplan.domains.namo.generators import A, B, _unseen_blocker, gen_move, region

    start, goal = Pt(1.0, 2.0), Pt(2.6, 2.0)  # one straight move
    b = NamoBelief(GEOM, np.array([start.x, start.y]), sensor=replace(DEFAULT_SENSOR, miss_prob=0.0))
    b.detect("box", 0.8, 0.75, 0.3, (0.4, 0.4))  # (1.8, 2.75), beside the way; its shadow reaches into it
    b.observed[:] = True  # no fog
    start = b.nominal()  # (the grid's point where the robot stands)
    r = region(b, start, goal, False)
    assert "box" in b.blockers(r, b.params.eps_clear) and not b.in_the_way(r, "box")
    starts = [o[A] for o in gen_move({B: goal}, Goal(), b, None)]
    assert starts == [start] and not _unseen_blocker(b, r)
    b.futile_looks[(start, "box")] = b.percept  # a look from the start did not find it
    assert _unseen_blocker(b, r)
    starts = [o[A] for o in gen_move({B: goal}, Goal(), b, None)]
    assert starts and start not in starts
    assert all(abs(a.x - 1.8) < 0.3 for a in starts)  # halfway
