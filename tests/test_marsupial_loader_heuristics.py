"""The loader's A* estimates (stow and fetch) are consistent, hence admissible: for every robot
operator from a configuration, h(before) <= cost + h(after), and h is 0 at the goal.  With a
closed set and no reopening, that is what makes the A* return cheapest paths."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.grid import SHAPES, SIZES, Hold, greedy_pack, occupancy
from nowplan.domains.marsupial.loader import Config

NAMES = ("p0", "p1", "p2", "p3", "p4")


@st.composite
def bays(draw: st.DrawFn) -> Config:
    """A bay: some packages packed in storage, maybe one at the door, the loader in a free cell."""
    rows, cols = draw(st.sampled_from(SIZES))
    shapes = draw(st.lists(st.sampled_from(sorted(SHAPES)), min_size=1, max_size=len(NAMES)))
    at_door = draw(st.booleans())
    door = (NAMES[0], shapes[0]) if at_door else None
    stow = shapes[1:] if at_door else shapes
    names = NAMES[1:] if at_door else NAMES
    spots = greedy_pack(rows, cols, [], stow, free_margin=2)
    if spots is None:
        stow, spots = [], []
    hold = Hold(rows, cols, tuple(sorted((names[i], s, spots[i]) for i, s in enumerate(stow))), (0, 0))
    occ = set(occupancy(hold, door))
    free = [(r, c) for r in range(rows) for c in range(cols) if (r, c) not in occ]
    loader = draw(st.sampled_from(free))
    conf: Config = (Hold(rows, cols, hold.items, loader), door)
    # a few random robot operators, so that held packages and the load region are covered too
    for _ in range(draw(st.integers(0, 6))):
        succ = lp.successors(conf)
        if not succ:
            break
        conf = succ[draw(st.integers(0, len(succ) - 1))][0].after
    return conf


def _consistent(h: lp.Heuristic, goal: lp.Goal, conf: Config) -> None:
    if goal(conf):
        assert h(conf) == 0.0
    for t, cost in lp.successors(conf):
        assert h(conf) <= cost + h(t.after) + 1e-9, (t.kind, t.arg, conf, t.after)


@settings(max_examples=150, deadline=None)
@given(bays())
def test_stow_estimate_is_consistent(conf: Config) -> None:
    _consistent(lp.stow_h, lp.stow_goal, conf)


@settings(max_examples=150, deadline=None)
@given(bays(), st.sampled_from(NAMES))
def test_fetch_estimate_is_consistent(conf: Config, pkg: str) -> None:
    if pkg not in conf[0].packages() and (conf[1] is None or conf[1][0] != pkg):
        return
    _consistent(lp.fetch_h(pkg), lp.fetch_goal(pkg), conf)


@settings(max_examples=25, deadline=None)
@given(bays(), st.sampled_from(NAMES))
def test_searches_find_the_cheapest_fetch(conf: Config, pkg: str) -> None:
    """A* with the estimate finds paths as cheap as uniform-cost search (h = 0) does."""
    if pkg not in conf[0].packages() and (conf[1] is None or conf[1][0] != pkg):
        return

    def cost(path: list[lp.Transition] | None) -> float | None:
        if path is None:
            return None
        return round(sum(c for t in path for u, c in lp.successors(t.before) if u == t), 9)

    informed = lp.search(conf, lp.fetch_goal(pkg), lp.fetch_h(pkg), max_nodes=3000)
    blind = lp.search(conf, lp.fetch_goal(pkg), lambda c: 0.0, max_nodes=3000)
    if blind is not None:
        assert cost(informed) == cost(blind)



def test_marsupial_effort_bound_is_below_every_small_plan_of_an_rchpn_run(monkeypatch) -> None:
    """On the beliefs of a real RCHPN run, the domain's effort bound of a step's exposed ``door``
    atoms is at most the cost of the small plan the estimator finds for them (or that plan does
    not exist), and the run makes the same moves, with fewer such small searches, as one where no
    bound spares a search."""
    from nowplan.acting.resources import Estimator
    from nowplan.domains.marsupial import model
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode

    checked: list[tuple[float, float]] = []
    original = Estimator._support

    def support(self, action, levels, crit):  # type: ignore[no-untyped-def]
        out = original(self, action, levels, crit)
        unmet = self._unmet(action, crit)
        if any(x.predicate == "door" for x in unmet):
            cost = float("inf") if out is None else sum(a.cost(self.belief) for a in out)
            checked.append((model.effort_bound(unmet, self.belief), cost))
        return out

    monkeypatch.setattr(Estimator, "_support", support)

    def moves() -> list[str]:
        ep = episode("both", 5, 0)
        _, _, ok = timed_run(ep, "hpn+peephole", 0, 120.0)
        assert ok
        return [str(a) for a in ep.world.asked]

    with_bound = moves()
    assert checked and any(b > 0 for b, _ in checked)
    assert all(b <= c + 1e-9 for b, c in checked), [x for x in checked if x[0] > x[1]]
    searched = len(checked)
    monkeypatch.setattr(Estimator, "effort_bound", lambda self, action, levels: 0.0)
    assert moves() == with_bound
    assert len(checked) - searched > searched  # the bound spared some of those small searches
