"""A domain's proof of no plan (``Domain.dead_end``): the regression planner answers "unsolvable"
without a search and leaves the random stream where the search would; marsupial's proof for a
package the loader cannot dig out holds where the search, unbudgeted, finds no plan."""

from __future__ import annotations

import random
from dataclasses import replace
from typing import Any

import pytest

from nowplan.acting import hpn as hpn_mod
from nowplan.core.atoms import Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.bay_relaxed import fetch_infeasible
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan

x = Var("x")
PREDS = {n: Predicate(n, 1) for n in ("a", "b", "c")}
OPS = (Operator("ab", (x,), (Precondition(atom("a", x), 1),), (atom("b", x),)),
       Operator("bc", (x,), (Precondition(atom("b", x), 1),), (atom("c", x),)))
CFG = PlannerConfig(engine="regression", serialization=True)
GOAL = Goal.of([atom("c", "k"), atom("b", "k"), atom("c", "m")])


def test_a_dead_end_answers_unsolvable_without_a_search_and_draws_as_the_search() -> None:
    plain = Domain("t", PREDS, OPS)
    proved = replace(plain, dead_end=lambda goal, belief, levels, objects: "c(m) is out of reach")
    objs = {"k": None, "m": None}
    r1, r2 = random.Random(7), random.Random(7)
    searched = plan(plain, objs, State(), GOAL, LevelMap(0), CFG, None, r1)
    answered = plan(proved, objs, State(), GOAL, LevelMap(0), CFG, None, r2)
    assert searched.status is PlanStatus.UNSOLVABLE and searched.expanded > 0
    assert answered.status is PlanStatus.UNSOLVABLE and answered.reason == "c(m) is out of reach"
    assert answered.expanded == 0 and answered.method == "dead_end"
    assert r1.random() == r2.random()  # the serialization's shuffle was drawn in both


def test_the_forward_engine_asks_the_dead_end_test_too() -> None:
    """A flat call searches forward (engine auto at a concrete level, or forward): the domain's proof
    answers it as it answers the regression (before: the forward search proved it again by exhausting
    its space, or ran out of nodes first; the held-out mill shop)."""
    proved = Domain("t", PREDS, OPS, dead_end=lambda goal, belief, levels, objects: "c(m) is out of reach")
    objs = {"k": None, "m": None}
    for engine in ("forward", "auto"):
        res = plan(proved, objs, State(), GOAL, LevelMap(0), replace(CFG, engine=engine))
        assert res.status is PlanStatus.UNSOLVABLE and res.reason == "c(m) is out of reach"
        assert res.method == "dead_end" and res.expanded == 0
    quiet = replace(proved, dead_end=lambda goal, belief, levels, objects: None)
    res = plan(quiet, {"k": None}, State([atom("a", "k")]), Goal.of([atom("c", "k")]), LevelMap(0),
               replace(CFG, engine="forward"))
    assert res.status is PlanStatus.SOLVED and res.method != "dead_end"


def test_no_proof_leaves_the_search_as_it_was() -> None:
    proved = Domain("t", PREDS, OPS, dead_end=lambda goal, belief, levels, objects: None)
    res = plan(proved, {"k": None}, State([atom("a", "k")]), Goal.of([atom("c", "k")]), LevelMap(0), CFG)
    assert res.status is PlanStatus.SOLVED and res.plan is not None and len(res.plan.actions) == 2


def test_level_of_a_key_is_the_level_of_its_action() -> None:
    op = OPS[0]
    a, b = op.instantiate({x: "k"}), op.instantiate({x: "m"})
    lm = LevelMap(3).next_level(a).next_level(a)
    floored = LevelMap(3, lm.overrides, frozenset({("ab", 1)}))
    for m in (LevelMap(3), lm, floored):
        assert m.level_of(a.key) == m.level(a) and m.level_of(b.key) == m.level(b)


# two tall packages wall the 3-row bay: p8 at the back cannot be dug out (test_marsupial_bay_relaxed)
WALLED = lp.Hold(3, 6, tuple(sorted([("p4", "dot", (0, 3)), ("p6", "tall", (0, 2)), ("p7", "dot", (1, 3)),
                                     ("p8", "tall", (0, 0))])), (2, 3))


def test_the_path_cache_tells_a_proof_from_a_search_cut_at_its_limit(monkeypatch: pytest.MonkeyPatch) -> None:
    test = lambda p: (lambda c: fetch_infeasible(c[0], c[1], p))  # noqa: E731
    start: lp.Config = (WALLED, None)
    cache = lp.PathCache()
    assert cache.path(start, "fetch:p8", lp.fetch_goal("p8"), lp.fetch_h("p8"), infeasible=test("p8")) is None
    assert cache.impossible(start, "fetch:p8")
    assert cache.path(start, "fetch:p4", lp.fetch_goal("p4"), lp.fetch_h("p4"), infeasible=test("p4"))
    assert not cache.impossible(start, "fetch:p4")
    # no relaxed test and a limit the search reaches: no path, and no proof either
    monkeypatch.setattr(lp, "SEARCH_NODES", 50)
    cut = lp.PathCache()
    assert cut.path(start, "fetch:p8", lp.fetch_goal("p8"), lp.fetch_h("p8")) is None
    assert not cut.impossible(start, "fetch:p8")


@pytest.mark.slow
@pytest.mark.parametrize("regime,n,trial", [("both", 5, 9)])
def test_every_buried_package_proof_is_a_subgoal_the_search_cannot_solve(
    regime: str, n: int, trial: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """An RCHPN run where the proof answers planner calls below given-up combinations: each of the
    first four such calls (distinct goals), searched without the proof and without a node budget,
    exhausts its space (each takes 0.4-1.5 s)."""
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode

    checked: list[str] = []
    make_plan = hpn_mod.Executive.make_plan

    def wrapped(self: Any, goal: Any, levels: Any, parent: Any, *args: Any, **kwargs: Any) -> Any:
        real = self._planner
        if not getattr(real, "_checks_dead_ends", False):
            def planner(domain: Any, objects: Any, belief: Any, goal: Any, levels: Any, cfg: Any,
                        context: Any, rng: Any) -> Any:
                state = rng.getstate()
                res = real(domain, objects, belief, goal, levels, cfg, context, rng)
                if res.method == "dead_end" and len(checked) < 4 and str(goal) not in checked:
                    again = random.Random()
                    again.setstate(state)
                    full = replace(cfg, call_nodes=0, max_nodes=200_000, shortcut_nodes=200_000)
                    res2 = real(replace(domain, dead_end=None), objects, belief, goal, levels, full, context, again)
                    assert res2.status is PlanStatus.UNSOLVABLE, (goal, res2.status, res2.reason)
                    checked.append(str(goal))
                return res
            planner._checks_dead_ends = True  # type: ignore[attr-defined]
            self._planner = planner
        return make_plan(self, goal, levels, parent, *args, **kwargs)

    monkeypatch.setattr(hpn_mod.Executive, "make_plan", wrapped)
    m, _, ok = timed_run(episode(regime, n, trial), "hpn+peephole", trial, 600.0)
    assert ok and checked
