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
