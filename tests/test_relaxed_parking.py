"""Achievers parked while the lazy relaxation explores (LazyRelaxed._unparked) change no estimate and no plan."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.core.levels import flat_levels
from nowplan.core.state import State
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search
from nowplan.planning.relaxed import LazyRelaxed
from tests.test_lmcut_lazy import FREE, family_nodes, free2_domain, v
from tests.test_planner_property import FAMILIES, QUICK, level_maps

CFG = PlannerConfig(heuristic="lmcut", lazy_relaxation=True, engine="regression")


def _search(domain: Domain, items: list[str], init: State, park: bool) -> _Search:
    srch = _Search(domain, {x: None for x in items}, init, flat_levels(), CFG, None)
    assert srch.relaxed is not None
    srch.relaxed.park = park
    return srch


def test_dominated_achievers_are_not_explored_and_the_value_stays():
    items = [f"i{k}" for k in range(12)]
    init = State([Atom("mine", ("i0",)), *(Atom("far", (x,)) for x in items[1:])])
    done = [Atom("done", ())]
    on, off = _search(FREE, items, init, True), _search(FREE, items, init, False)
    assert on.h(on.table.ids_of(done)) == off.h(off.table.ids_of(done)) == 6.0  # finish + drop(i0)
    assert on.relaxed is not None and off.relaxed is not None
    # drop(i1..i11) wait, parked, and fetch/walk behind them are never grounded
    assert on.relaxed.parked_count == 11
    assert len(on.relaxed._acts) == 2 < len(off.relaxed._acts)


def test_a_parked_achiever_is_registered_once_another_fact_needs_it():
    """drop2(i1) frees the hands (dominated by drop(i0)) and brings i1 near, which ``both`` needs."""
    dom = free2_domain()
    init = State([Atom("mine", ("i0",)), Atom("far", ("i1",))])
    on, off = _search(dom, ["i0", "i1"], init, True), _search(dom, ["i0", "i1"], init, False)
    done = [Atom("done", ())]
    assert on.h(on.table.ids_of(done)) == off.h(off.table.ids_of(done))
    r = on.relaxed
    assert r is not None and not r._parked  # asked for by near(i1): registered for free() too
    free = on.table.ids_of([Atom("free", ())])
    (f,) = free
    names = sorted(str(r._acts[a]) for a in r._achieved_by[f])
    assert any(n.startswith("drop2(i1") for n in names), names


class Twin:
    """Replaces LazyRelaxed.estimate: a parking relaxation's value checked against an unparked twin's."""

    def __init__(self) -> None:
        self.calls = 0
        self.parked = 0
        self.original = LazyRelaxed.estimate

    def __call__(self, r: LazyRelaxed, fs: frozenset[int]) -> float:
        if not r.park:
            return self.original(r, fs)
        twin: Any = r.__dict__.get("_twin")
        if twin is None:
            twin = r.__dict__["_twin"] = LazyRelaxed(r.achievers, r.holds, r.kind, r.context_key, r.unknown,
                                                    r.recontext, park=False)
        twin.kind = r.kind
        a, b = self.original(r, fs), self.original(twin, fs)
        assert a == b, (sorted(fs), a, b)
        self.calls += 1
        self.parked = max(self.parked, r.parked_count)
        return a


@pytest.mark.parametrize("family", sorted(set(FAMILIES) - {"hanoi"}))
@pytest.mark.parametrize("heuristic", ["lmcut", "hmax"])
@pytest.mark.timeout(300, method="thread")
@settings(max_examples=6, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_random_strips_estimates_equal_an_unparked_twin(family, heuristic, data):
    case = data.draw(FAMILIES[family], label="case")
    config = replace(QUICK, heuristic=heuristic, lazy_relaxation=True, engine="regression",
                     max_nodes=family_nodes(family, 150), shortcut_nodes=50)
    objects = {o: None for o in case.objects}
    chk = Twin()
    LazyRelaxed.estimate = lambda self, fs: chk(self, fs)  # type: ignore[method-assign]
    try:
        for _, levels in data.draw(level_maps(case), label="levels"):
            plan(case.domain, objects, case.init, case.goal, levels, config)
    finally:
        LazyRelaxed.estimate = chk.original  # type: ignore[method-assign]


@pytest.mark.parametrize("regime,n", [("single", 5), ("both", 5)])
def test_marsupial_hpn_same_plans_with_and_without_parking(monkeypatch, regime, n):
    """Marsupial's generators read the goal, so values may depend on the exploration's order: the plans
    and expanded nodes of every call are compared instead (the executed actions follow)."""
    from nowplan.acting.metrics import Outcome
    from nowplan.domains.marsupial.scenarios import episode
    from tests.test_marsupial import _checked_run

    runs = []
    made: list[LazyRelaxed] = []
    for park in (True, False):
        calls: list[tuple[Any, ...]] = []
        orig = LazyRelaxed.__init__

        def init(self: LazyRelaxed, *a: Any, _orig: Any = orig, _park: bool = park, **kw: Any) -> None:
            _orig(self, *a, **{**kw, "park": _park and kw.get("park", False)})
            if _park:
                made.append(self)

        monkeypatch.setattr(LazyRelaxed, "__init__", init)
        import nowplan.acting.hpn as hpn_mod

        planner = hpn_mod.regression_plan

        def counted(*a: Any, _p: Any = planner, _calls: list[tuple[Any, ...]] = calls, **kw: Any) -> Any:
            res = _p(*a, **kw)
            _calls.append((res.expanded, res.generated, None if res.plan is None else
                           tuple((str(s.action), s.goal) for s in res.plan.steps)))
            return res

        monkeypatch.setattr(hpn_mod, "regression_plan", counted)
        m, bad, _ = _checked_run(episode(regime, n, 0), "hpn", 0)
        assert m.outcome is Outcome.REACHED and not bad
        runs.append(calls)
        monkeypatch.undo()
    assert len(runs[0]) > 40 and runs[0] == runs[1]
    assert sum(r.parked_count for r in made) > 0  # (parking took place)


@pytest.mark.parametrize("fetch_cost", [3.0, 0.0])
def test_achievers_listed_before_the_dominating_one(fetch_cost):
    """The held item is the last one: drops listed before drop(i11) cost as much.  They are parked only
    where a precondition of theirs cannot cost 0 (``mine`` is made by fetch, of cost 3); with a free
    fetch they could be LM-cut's first cheapest achiever of ``free`` with preconditions of cost 0."""
    ops = tuple(replace(o, cost=fetch_cost) if o.name == "fetch" else o for o in FREE.operators)
    dom = Domain("free3", FREE.predicates, ops)
    items = [f"i{k}" for k in range(12)]
    init = State([Atom("mine", ("i11",)), *(Atom("far", (x,)) for x in items[:-1])])
    done = [Atom("done", ())]
    on, off = _search(dom, items, init, True), _search(dom, items, init, False)
    assert on.h(on.table.ids_of(done)) == off.h(off.table.ids_of(done)) == 6.0
    r = on.relaxed
    assert r is not None
    names = [str(a).split(",")[0] for a in r._acts]
    first = [str(s[0]) for s in on._supporters(on.table.id(Atom("free", ())), frozenset())]
    before = [n.split(",")[0] for n in first[: next(i for i, n in enumerate(first) if "i11" in n)]]
    assert before  # (some drops are listed before drop(i11))
    if fetch_cost > 0:
        assert r.parked_count == 11 and not any(n in names for n in before)
    else:
        assert r.parked_count == 11 - len(before) and all(n in names for n in before)
