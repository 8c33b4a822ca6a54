"""Deferred successors of held facts in the regression search (nowplan.planning.deferred).

Where no generator reads the goal, the lazy relaxation's costs do not depend on the
order in which facts are explored, so the deferred search must expand the same nodes in
the same order as the eager one: the same plans, pre-images and node counts, checked on
the property test's random STRIPS families at every level.  On marsupial (generators
that read the goal) HPN's executed actions are compared with deferral on and off.
"""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.atoms import Var
from nowplan.core.state import State
from nowplan.planning.deferred import Reach
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search
from tests.test_lmcut_lazy import family_nodes
from tests.test_planner_property import FAMILIES, QUICK, check_contract, level_maps, witness_reaches_goal


def _steps(res):
    if res.plan is None:
        return None
    return [(None if s.action is None else s.action.key, frozenset(s.goal.atoms)) for s in res.plan.steps]


def _both(monkeypatch, *args):
    out = []
    for defer in (False, True):
        monkeypatch.setattr(_Search, "defer_held", defer)
        out.append(plan(*args))
    return out


# ------------------------------------------------------------------ a held fact that must be re-achieved

x, y = Var("x"), Var("y")
BLOCKS = Domain(
    "blocks3",
    {"on": Predicate("on", 2), "ontable": Predicate("ontable", 1), "clear": Predicate("clear", 1),
     "holding": Predicate("holding", 1), "handempty": Predicate("handempty", 0)},
    (
        Operator("pickup", (x,), (Precondition(Atom("clear", (x,)), 1), Precondition(Atom("ontable", (x,)), 1),
                                  Precondition(Atom("handempty", ()), 1)),
                 (Atom("ontable", (x,), False), Atom("clear", (x,), False), Atom("handempty", (), False),
                  Atom("holding", (x,)))),
        Operator("putdown", (x,), (Precondition(Atom("holding", (x,)), 1),),
                 (Atom("holding", (x,), False), Atom("ontable", (x,)), Atom("clear", (x,)), Atom("handempty", ()))),
        Operator("stack", (x, y), (Precondition(Atom("holding", (x,)), 1), Precondition(Atom("clear", (y,)), 1)),
                 (Atom("holding", (x,), False), Atom("clear", (y,), False), Atom("on", (x, y)),
                  Atom("clear", (x,)), Atom("handempty", ()))),
        Operator("unstack", (x, y), (Precondition(Atom("on", (x, y)), 1), Precondition(Atom("clear", (x,)), 1),
                                     Precondition(Atom("handempty", ()), 1)),
                 (Atom("on", (x, y), False), Atom("clear", (x,), False), Atom("handempty", (), False),
                  Atom("holding", (x,)), Atom("clear", (y,)))),
    ),
)


def test_reach_bounds_by_the_unmet_facts_no_achiever_names():
    """on(a, b)'s achiever stack(a, b) names holding(a), clear(b), on(a, b), clear(a), handempty."""
    reach = Reach(BLOCKS)
    T = BLOCKS.facts
    on_ab = T.id(Atom("on", ("a", "b")))
    c, pats = reach(on_ab)
    assert c == 1.0 and pats
    unmet = [(T.id(Atom("holding", ("a",))), 5.0), (T.id(Atom("on", ("c", "d"))), 3.0), (T.id(Atom("clear", ("c",))), 2.0)]
    assert reach.bound(on_ab, unmet) == (1.0, 3.0)  # holding(a) is named; on(c, d) and clear(c) are not
    assert reach.bound(on_ab, unmet[:1]) == (1.0, 0.0)
    assert reach.bound(on_ab, []) == (1.0, 0.0)
    ontable = T.id(Atom("ontable", ("a",)))  # putdown(a): names holding(a), ontable(a), clear(a), handempty
    assert reach.bound(ontable, [(T.id(Atom("clear", ("c",))), 2.0), (T.id(Atom("clear", ("a",))), 4.0)]) == (1.0, 2.0)
    assert Reach(BLOCKS).bound(ontable, [(T.id(Atom("clear", ("a",))), 4.0)]) == (1.0, 0.0)  # the memo, per domain
    assert reach(on_ab) is reach(on_ab)  # kept per domain


@pytest.mark.parametrize("heuristic", ["lmcut", "hmax", "hadd"])
def test_a_held_goal_fact_is_undone_and_re_achieved(monkeypatch, heuristic):
    """on(a, b) holds but b must go onto c first: the plan's last step re-achieves a held fact."""
    init = State([Atom("on", ("a", "b")), Atom("ontable", ("b",)), Atom("ontable", ("c",)),
                  Atom("clear", ("a",)), Atom("clear", ("c",)), Atom("handempty", ())])
    goal = Goal.of([Atom("on", ("a", "b")), Atom("on", ("b", "c"))])
    cfg = PlannerConfig(heuristic=heuristic, lazy_relaxation=True, serialization=False, monotonic=False,
                        engine="regression")
    objects = {o: None for o in "abc"}
    eager, deferred = _both(monkeypatch, BLOCKS, objects, init, goal, flat_levels(), cfg)
    assert deferred.status is PlanStatus.SOLVED and deferred.plan is not None
    assert _steps(deferred) == _steps(eager)
    assert deferred.expanded == eager.expanded
    assert deferred.generated < eager.generated  # some held facts' successors were never made
    last = deferred.plan.steps[-1].action
    assert last is not None and last.key == ("stack", ("a", "b"))  # re-achieves on(a, b), which held
    if heuristic != "hadd":  # admissible: the optimal 6 steps
        assert len(deferred.plan) == 6


# ------------------------------------------------------------------ property: the same search as eager

# 300 expansions, as the sibling property tests keep theirs small (test_lmcut_lazy, test_relaxed_parking):
# both searches are cut alike, and the deterministic draws include blocks cases whose LM-cut nodes are
# dear (35 s of the suite at 1,000)
LAZY = [replace(QUICK, heuristic=h, lazy_relaxation=True, engine="regression", max_nodes=300)
        for h in ("lmcut", "hmax", "hadd")]


@pytest.mark.parametrize("family", sorted(set(FAMILIES) - {"hanoi"}))
@pytest.mark.timeout(300, method="thread")
@settings(max_examples=8, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_deferral_expands_what_eager_search_expands(family, data):
    case = data.draw(FAMILIES[family], label="case")
    witness_reaches_goal(case)
    base = data.draw(st.sampled_from(LAZY), label="config")
    base = replace(base, max_nodes=family_nodes(family, base.max_nodes))
    shortcuts = data.draw(st.booleans(), label="shortcuts")
    config = replace(base, serialization=shortcuts, monotonic=shortcuts, seed=data.draw(st.integers(0, 3)))
    objects = {o: None for o in case.objects}
    for name, levels in data.draw(level_maps(case), label="levels"):
        runs = []
        for defer in (False, True):
            _Search.defer_held = defer
            try:
                runs.append(plan(case.domain, objects, case.init, case.goal, levels, config))
            finally:
                _Search.defer_held = True
        eager, deferred = runs
        assert deferred.status is eager.status, (name, deferred.reason, eager.reason)
        assert deferred.expanded == eager.expanded, name
        assert _steps(deferred) == _steps(eager), name
        if deferred.status is PlanStatus.SOLVED:
            check_contract(case, levels, deferred, concrete=name == "flat")


# ------------------------------------------------------------------ marsupial: generators that read the goal


@pytest.mark.parametrize("regime", ["single", "both"])
def test_marsupial_hpn_makes_the_same_decisions_with_deferral(monkeypatch, regime):
    from nowplan.acting.metrics import Outcome
    from tests.test_marsupial import _checked_run
    from nowplan.domains.marsupial.scenarios import episode

    runs = []
    for defer in (False, True):
        monkeypatch.setattr(_Search, "defer_held", defer)
        m, bad, executed = _checked_run(episode(regime, 4, 0), "hpn", 0)
        assert m.outcome is Outcome.REACHED and not bad
        runs.append((executed, m.execution_cost, m.plans_made))
    assert runs[0] == runs[1]


def test_top_level_marsupial_plan_is_the_same_with_deferral(monkeypatch):
    from nowplan.domains.marsupial.model import PLANNER
    from nowplan.domains.marsupial.problems import generate

    prob, _ = generate("both", 6, 1)
    eager, deferred = _both(monkeypatch, prob.domain, prob.objects, _belief(prob), prob.goal,
                            LevelMap(prob.domain.top_level), PLANNER)
    assert deferred.status is PlanStatus.SOLVED
    assert _steps(deferred) == _steps(eager)
    assert deferred.generated < eager.generated


def _belief(prob):
    from nowplan.belief.symbolic import SymbolicBelief

    return SymbolicBelief(prob.init)


def test_an_action_of_infinite_cost_is_never_kept():
    """Eager search skips a child whose cost is infinite (ng >= best_g); so does the stamped search."""
    dom = Domain(
        "inf", {"p": Predicate("p", 0), "q": Predicate("q", 0)},
        (Operator("never", (), (), (Atom("p", ()),), cost=lambda b, s: float("inf")),
         Operator("step", (), (), (Atom("p", ()),), cost=1.0)),
    )
    cfg = PlannerConfig(heuristic="lmcut", lazy_relaxation=True, engine="regression")
    res = plan(dom, {}, State([Atom("q", ())]), Goal.of([Atom("p", ()), Atom("q", ())]), flat_levels(), cfg)
    assert res.status is PlanStatus.SOLVED and res.plan is not None
    assert [s.action.name for s in res.plan.steps[1:]] == ["step"]


# ------------------------------------------------------------------ postponed successors of unmet facts


def test_kept_cost_is_the_dearest_unmet_fact_the_action_leaves_alone():
    from nowplan.planning.deferred import kept_cost
    from nowplan.planning.subgoals import action_facts

    T = BLOCKS.facts
    stack = next(o for o in BLOCKS.operators if o.name == "stack")
    act = stack.instantiate({v: x for v, x in zip(stack.params, ("a", "b"))})
    info = action_facts(T, act, None, frozenset())
    holding, on_cd, clear_c = (T.id(Atom("holding", ("a",))), T.id(Atom("on", ("c", "d"))),
                               T.id(Atom("clear", ("c",))))
    # stack(a, b) needs holding(a) (a precondition's fluent): only on(c, d) and clear(c) stay as they are
    assert kept_cost(T.fluent, info, [(holding, 5.0), (on_cd, 3.0), (clear_c, 2.0)]) == 3.0
    assert kept_cost(T.fluent, info, [(holding, 5.0)]) == 0.0
    assert kept_cost(T.fluent, info, []) == 0.0


def test_dear_achievers_of_an_unmet_fact_wait_and_change_no_plan(monkeypatch):
    """A loaded truck must stow its door to pack: every package's Unload also clears the door (cost 10,
    against the loader's 1); those children wait in an entry that never comes first."""
    from nowplan.belief.symbolic import SymbolicBelief
    from nowplan.core.atoms import atom
    from nowplan.domains.marsupial.model import PLANNER
    from nowplan.domains.marsupial.problems import generate

    prob, _ = generate("both", 8, 1)
    d = prob.domain
    reach = {x[0] for x in prob.init.facts("reachable") if x[1] == "truck0"}
    pkg, loc = next((p, x) for p, x in prob.init.facts("at") if str(p).startswith("p") and x in reach)
    here = next(x for v, x in prob.init.facts("at") if v == "truck0")
    load = next(o for o in d.operators if o.name == "load")
    loaded = load.instantiate(dict(zip(load.params, (pkg, "truck0", loc))))
    state = prob.init.apply([atom("at", "truck0", here, value=False), atom("at", "truck0", loc)])
    state = state.apply(loaded.effects())
    goal = Goal.of([atom("packed", "truck0")], d.rules)
    runs = []
    for post in (False, True):
        monkeypatch.setattr(_Search, "postpone_unmet", post)
        runs.append(plan(d, prob.objects, SymbolicBelief(state), goal, LevelMap(1), PLANNER))
    made, waited = runs
    assert waited.status is PlanStatus.SOLVED and _steps(waited) == _steps(made)
    assert waited.expanded == made.expanded
    assert waited.generated < made.generated / 4  # the Unloads were never regressed nor estimated
