"""A move whose volume a look from its start failed to reveal is approached via a halfway point."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.core.atoms import Goal  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.generators import A, B, gen_move, region  # noqa: E402
from nowplan.domains.namo.geometry import MapGeometry, Pt  # noqa: E402


def _moves(belief: NamoBelief, b: Pt) -> list[Pt]:
    return [o[A] for o in gen_move({B: b}, Goal(()), belief, None)]


def test_a_futile_look_sends_the_move_through_a_halfway_point() -> None:
    belief = NamoBelief(MapGeometry(6.0, 3.0, ()), np.array([1.0, 1.5]))
    start, b = belief.nominal(), Pt(2.6, 1.5)
    assert _moves(belief, b) == [start]  # straight, 1.6 m, through fog
    r = region(belief, start, b, False)
    assert not belief.is_observed(r)
    # a look from the start did not reveal it (something unseen hides the fog) and nothing new since
    belief.futile_looks[(r.view, f"look:{r}")] = belief.percept
    (mid,) = _moves(belief, b)
    assert mid != start and 0.5 < mid.dist(start) < 1.1 and mid.dist(b) < 1.1
    belief._bump(percept=True)  # something new was seen: the look from the start is worth trying again
    assert _moves(belief, b) == [start]
