"""LM-cut over the lazy relaxation on its pruned graph (nowplan.planning.lmcut_lazy) gives the whole graph's value."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.planning.lmcut_lazy import cut_graph, lmcut_part
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search
from nowplan.planning.relaxed import LazyRelaxed
from tests.test_planner_property import FAMILIES, QUICK, level_maps

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"


class Checked:
    """Replaces LazyRelaxed._lmcut: both graphs' values, asserted equal; counts the pruned graphs' sizes."""

    def __init__(self) -> None:
        self.calls = 0
        self.pruned = 0
        self.whole = 0

    def __call__(self, r: LazyRelaxed, goal: list[int]) -> float:
        a, b = lmcut_part(r, goal), lmcut_part(r, goal, prune=False)
        assert a == b, (goal, a, b)
        self.calls += 1
        self.pruned += len(cut_graph(r, goal)[1])
        self.whole += len(r._relevant(goal)[1])
        return a


def _patch(monkeypatch) -> Checked:
    chk = Checked()
    monkeypatch.setattr(LazyRelaxed, "_lmcut", lambda self, goal: chk(self, goal))
    return chk


# ------------------------------------------------------------------ a fact with many dominated achievers

v, w = Var("v"), Var("w")
FREE = Domain(
    "free",
    {"free": Predicate("free", 0), "mine": Predicate("mine", 1), "near": Predicate("near", 1),
     "far": Predicate("far", 1), "done": Predicate("done", 0)},
    (
        # free() by dropping one's own item (which holds) or any other item (which must be fetched first)
        Operator("drop", (v,), (Precondition(Atom("mine", (v,)), 1),), (Atom("free", ()),), cost=5.0),
        Operator("fetch", (v,), (Precondition(Atom("near", (v,)), 1),), (Atom("mine", (v,)),), cost=3.0),
        Operator("walk", (v,), (Precondition(Atom("far", (v,)), 1),), (Atom("near", (v,)),), cost=2.0),
        Operator("finish", (), (Precondition(Atom("free", ()), 1),), (Atom("done", ()),), cost=1.0),
    ),
)


def test_dominated_achievers_leave_the_graph_and_the_value_stays():
    items = [f"i{k}" for k in range(12)]
    init = State([Atom("mine", ("i0",)), *(Atom("far", (x,)) for x in items[1:])])
    objects = {x: None for x in items}
    srch = _Search(FREE, objects, init, flat_levels(),
                   PlannerConfig(heuristic="lmcut", lazy_relaxation=True, engine="regression"), None)
    r = srch.relaxed
    assert r is not None
    r.park = False  # every drop explored (parking leaves them out before the graph: test_relaxed_parking.py)
    done = srch.table.ids_of([Atom("done", ())])
    assert srch.h(done) == 6.0  # finish (1) + drop(i0) (5)
    goal = [f for f in done if r.val.get(f, 0.0) > 0.0]
    _, pruned, _ = cut_graph(r, goal)
    _, whole, _ = r._relevant(goal)
    assert len(pruned) == 2 < len(whole)  # finish and drop(i0); every other drop (and its chain) is dominated
    assert lmcut_part(r, goal) == lmcut_part(r, goal, prune=False) == 6.0


def free2_domain() -> Domain:
    """FREE with drop2(v): it frees the hands (dominated by drop(i0)) and brings v near, which both(v) needs."""
    return Domain(
        "free2", FREE.predicates,
        (*FREE.operators[:1],
         Operator("drop2", (v,), (Precondition(Atom("far", (v,)), 1),), (Atom("free", ()), Atom("near", (v,))),
                  cost=5.0),
         Operator("both", (v,), (Precondition(Atom("free", ()), 1), Precondition(Atom("near", (v,)), 1)),
                  (Atom("done", ()),), cost=1.0)),
    )


def test_a_dominated_achiever_comes_back_when_its_other_target_is_needed():
    """drop(i1) also makes near(i1) here; with near(i1) in the graph it is no longer covered by drop(i0)."""
    dom = free2_domain()
    init = State([Atom("mine", ("i0",)), Atom("far", ("i1",))])
    srch = _Search(dom, {"i0": None, "i1": None}, init, flat_levels(),
                   PlannerConfig(heuristic="lmcut", lazy_relaxation=True, engine="regression"), None)
    r = srch.relaxed
    assert r is not None
    done = srch.table.ids_of([Atom("done", ())])
    h = srch.h(done)
    goal = [f for f in done if r.val.get(f, 0.0) > 0.0]
    _, pruned, _ = cut_graph(r, goal)
    names = sorted(str(r._acts[a]) for a in pruned)
    assert any(n.startswith("drop2(i1") for n in names), names
    assert lmcut_part(r, goal) == lmcut_part(r, goal, prune=False) == h


# ------------------------------------------------------------------ the same values where the planner asks


@pytest.mark.parametrize("regime,n", [("single", 4), ("both", 5)])
def test_marsupial_hpn_cuts_are_equal_on_both_graphs(monkeypatch, regime, n):
    from nowplan.acting.metrics import Outcome
    from nowplan.domains.marsupial.scenarios import episode
    from tests.test_marsupial import _checked_run

    chk = _patch(monkeypatch)
    m, bad, _ = _checked_run(episode(regime, n, 0), "hpn", 0)
    assert m.outcome is Outcome.REACHED and not bad
    assert chk.calls > 50 and chk.pruned < chk.whole


def test_logistics_cuts_are_equal_on_both_graphs(monkeypatch):
    from nowplan.io.pddl_read import load_pddl

    chk = _patch(monkeypatch)
    prob = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p03.pddl")
    cfg = PlannerConfig(heuristic="lmcut", lazy_relaxation=True, engine="regression", max_nodes=60,
                        shortcut_nodes=30, clock="cpu", time_limit=600.0)
    for levels in (flat_levels(), LevelMap(0)):  # solved or not: every cut asked for is compared
        plan(prob.domain, prob.objects, prob.init, prob.goal, levels, cfg)
    assert chk.calls > 20


def family_nodes(family: str, nodes: int) -> int:
    """Expansions for a property search over ``family``: a third for blocks, whose LM-cut nodes cost
    ~8 ms each in Python (the seeded blocks draws made each such test ~20 s; a third of the nodes still
    compares thousands of estimates)."""
    return nodes // 3 if family == "blocks" else nodes


@pytest.mark.parametrize("family", sorted(set(FAMILIES) - {"hanoi"}))
@pytest.mark.timeout(300, method="thread")
@settings(max_examples=6, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_random_strips_cuts_are_equal_on_both_graphs(family, data):
    case = data.draw(FAMILIES[family], label="case")
    config = replace(QUICK, heuristic="lmcut", lazy_relaxation=True, engine="regression",
                     max_nodes=family_nodes(family, 150), shortcut_nodes=50)
    objects = {o: None for o in case.objects}
    original = LazyRelaxed._lmcut
    chk = Checked()
    LazyRelaxed._lmcut = lambda self, goal: chk(self, goal)  # type: ignore[method-assign]
    try:
        for _, levels in data.draw(level_maps(case), label="levels"):
            plan(case.domain, objects, case.init, case.goal, levels, config)
    finally:
        LazyRelaxed._lmcut = original  # type: ignore[method-assign]


