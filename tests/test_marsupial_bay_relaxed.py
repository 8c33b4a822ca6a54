"""The relaxed bay search (loader cell forgotten) proves a fetch impossible only where the loader's
own search fails, and the path cache gives the same answers with it as without."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.bay_relaxed import fetch_infeasible
from nowplan.domains.marsupial.grid import SHAPES, Hold, cells, occupancy
from nowplan.domains.marsupial.loader import Config

# two tall packages wall the 3-row bay: p8 at the back cannot be dug out (the loader's search
# expands some 20 000 configurations to find that out)
WALLED = Hold(3, 6, tuple(sorted([("p4", "dot", (0, 3)), ("p6", "tall", (0, 2)), ("p7", "dot", (1, 3)),
                                  ("p8", "tall", (0, 0))])), (2, 3))


def test_a_walled_package_is_proved_unfetchable_and_the_loader_agrees() -> None:
    assert fetch_infeasible(WALLED, None, "p8")
    assert lp.search((WALLED, None), lp.fetch_goal("p8"), lp.fetch_h("p8"), max_nodes=200_000) is None
    # the packages in front can be fetched: no proof
    assert not fetch_infeasible(WALLED, None, "p4")
    assert lp.search((WALLED, None), lp.fetch_goal("p4"), lp.fetch_h("p4")) is not None


def test_the_path_cache_answers_as_without_the_test() -> None:
    cache = lp.PathCache()
    test = lambda p: (lambda c: fetch_infeasible(c[0], c[1], p))  # noqa: E731
    start: Config = (WALLED, None)
    assert cache.path(start, "fetch:p8", lp.fetch_goal("p8"), lp.fetch_h("p8"), infeasible=test("p8")) is None
    assert cache.relaxed_proofs == 1
    plain = lp.PathCache()
    for p in ("p4", "p6", "p7"):
        got = cache.path(start, f"fetch:{p}", lp.fetch_goal(p), lp.fetch_h(p), infeasible=test(p))
        assert got == plain.path(start, f"fetch:{p}", lp.fetch_goal(p), lp.fetch_h(p))


NAMES = ("p0", "p1", "p2", "p3", "p4")


@st.composite
def bays(draw: st.DrawFn) -> Config:
    """A 3x6 bay with packages set down anywhere they fit (not packed: walls and pockets too)."""
    rows, cols = 3, 6
    hold = Hold(rows, cols, (), (0, 0))
    door = None
    for name in NAMES[: draw(st.integers(1, len(NAMES)))]:
        shape = draw(st.sampled_from(sorted(SHAPES)))
        taken = set(occupancy(hold, door))
        free = [(r, c) for r in range(rows) for c in range(cols)
                if all(0 <= x[0] < rows and 0 <= x[1] < cols and x not in taken for x in cells(shape, (r, c)))]
        if not free:
            continue
        at = draw(st.sampled_from(free))
        if at == (0, cols - 2) and door is None and draw(st.booleans()):
            door = (name, shape)
        else:
            hold = hold.with_items([*hold.items, (name, shape, at)])
    taken = set(occupancy(hold, door))
    free = [(r, c) for r in range(rows) for c in range(cols) if (r, c) not in taken]
    if not free:
        return (Hold(rows, cols, (), (0, 0)), None)
    return (Hold(rows, cols, hold.items, draw(st.sampled_from(free))), door)


def _check(conf: Config, pkg: str) -> None:
    hold, door = conf
    if pkg not in hold.packages() and (door is None or door[0] != pkg):
        return
    if fetch_infeasible(hold, door, pkg):
        assert lp.search(conf, lp.fetch_goal(pkg), lp.fetch_h(pkg), max_nodes=500_000) is None, (conf, pkg)


@settings(max_examples=40, deadline=None)
@given(bays(), st.sampled_from(NAMES))
def test_a_relaxed_proof_means_the_loader_cannot_fetch(conf: Config, pkg: str) -> None:
    _check(conf, pkg)


@pytest.mark.slow
@settings(max_examples=400, deadline=None)
@given(bays(), st.sampled_from(NAMES))
def test_a_relaxed_proof_means_the_loader_cannot_fetch_many(conf: Config, pkg: str) -> None:
    _check(conf, pkg)
