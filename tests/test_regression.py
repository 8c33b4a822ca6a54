from __future__ import annotations

import pytest

from nowplan.core.atoms import Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.logistics import DOMAIN as LOG
from nowplan.domains.logistics import SIZES, generate
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan, preimage
from tests.helpers import replay

x, y = Var("x"), Var("y")
PREDS = {n: Predicate(n, 1) for n in ("a", "b", "c", "d")}


def _op(name, pre, eff, crit=1):
    return Operator(name, (x,), tuple(Precondition(p, crit) for p in pre), tuple(eff))


def test_preimage_removes_achieved_adds_preconditions():
    dom = Domain("t", PREDS, (_op("o", [atom("a", x)], [atom("b", x), atom("c", x, value=False)]),))
    act = dom.operators[0].instantiate({x: "k"})
    g = Goal.of([atom("b", "k"), atom("d", "k")])
    pre = preimage(g, act, None, dom)
    assert pre == Goal.of([atom("a", "k"), atom("d", "k")])


def test_preimage_fails_when_action_destroys_goal():
    dom = Domain("t", PREDS, (_op("o", [], [atom("b", x), atom("c", x, value=False)]),))
    act = dom.operators[0].instantiate({x: "k"})
    assert preimage(Goal.of([atom("b", "k"), atom("c", "k")]), act, None, dom) is None


def test_preimage_fails_when_precondition_contradicts_goal():
    dom = Domain("t", PREDS, (_op("o", [atom("d", x, value=False)], [atom("b", x)]),))
    act = dom.operators[0].instantiate({x: "k"})
    assert preimage(Goal.of([atom("b", "k"), atom("d", "k")]), act, None, dom) is None


def test_preimage_keeps_only_critical_preconditions_at_a_level():
    op = Operator("o", (x,), (Precondition(atom("a", x), 2), Precondition(atom("c", x), 1)), (atom("b", x),))
    dom = Domain("t", PREDS, (op,))
    act = op.instantiate({x: "k"})
    assert preimage(Goal.of([atom("b", "k")]), act, 1, dom) == Goal.of([atom("a", "k")])
    assert preimage(Goal.of([atom("b", "k")]), act, 0, dom) == Goal.of([atom("a", "k"), atom("c", "k")])


def test_plan_invariants_chain():
    dom, objs, init, goal = _chain_problem()
    res = plan(dom, objs, init, goal, flat_levels())
    assert res.status is PlanStatus.SOLVED and res.plan is not None
    assert [a.name for a in res.plan.actions] == ["ab", "bc"]
    assert res.plan.goal == Goal.of([atom("c", "k")])
    replay(dom, init, res.plan)


def test_unreachable_goal_is_unsolvable_not_an_exception():
    dom = Domain("t", PREDS, (_op("ab", [atom("a", x)], [atom("b", x)]),))
    regr = PlannerConfig(engine="regression")
    res = plan(dom, {"k": None}, State(), Goal.of([atom("b", "k")]), flat_levels(), regr)
    assert res.status is PlanStatus.UNSOLVABLE and "exhausted" in res.reason and res.plan is None
    # the forward engine sees it before searching: no action reaches b(k)
    fwd = plan(dom, {"k": None}, State(), Goal.of([atom("b", "k")]), flat_levels())
    assert fwd.status is PlanStatus.UNSOLVABLE and "b(k)" in fwd.reason and fwd.method == "forward:lama"


def test_node_limit_is_reported():
    size = SIZES["medium"]
    prob = generate(size, 1)
    cfg = PlannerConfig(max_nodes=3, shortcut_nodes=2, heuristic="count", engine="regression")
    res = plan(LOG, prob.objects, prob.init, prob.goal, flat_levels(), cfg)
    assert res.status is PlanStatus.NODE_LIMIT and "3 nodes" in res.reason
    fwd = plan(LOG, prob.objects, prob.init, prob.goal, flat_levels(), PlannerConfig(max_nodes=3))
    assert fwd.status is PlanStatus.NODE_LIMIT and "3 states" in fwd.reason


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("size", ["tiny", "small"])
def test_logistics_flat_plans_replay(size, seed):
    prob = generate(SIZES[size], seed)
    res = plan(LOG, prob.objects, prob.init, prob.goal, flat_levels())
    assert res.solved, res.reason
    replay(LOG, prob.init, res.plan)


@pytest.mark.parametrize("seed", range(3))
def test_logistics_abstract_plans_are_right_at_their_level(seed):
    prob = generate(SIZES["small"], seed)
    res = plan(LOG, prob.objects, prob.init, prob.goal, LevelMap(LOG.top_level))
    assert res.solved
    # at the top level only package positions matter; vehicle moves are hidden
    assert all(not a.name.startswith(("drive", "fly")) for a in res.plan.actions)
    replay(LOG, prob.init, res.plan, concrete=False)


@pytest.mark.parametrize("flags", [(True, True), (False, True), (True, False), (False, False)])
def test_shortcuts_can_be_switched_off(flags):
    ser, mono = flags
    prob = generate(SIZES["small"], 2)
    cfg = PlannerConfig(serialization=ser, monotonic=mono)
    res = plan(LOG, prob.objects, prob.init, prob.goal, LevelMap(LOG.top_level), cfg)
    assert res.solved
    if not ser:
        assert not any(a.startswith("serialization") for a in res.attempts)
    if not mono:
        assert not any(a.startswith("monotonic") for a in res.attempts)


def test_the_time_limit_runs_on_the_configured_clock(monkeypatch):
    import itertools
    import time

    from nowplan.errors import UsageError

    dom, objs, state, goal = _chain_problem()
    for engine in ("regression", "forward"):
        cfg = PlannerConfig(time_limit=5.0, clock="cpu", engine=engine)
        assert plan(dom, objs, state, goal, config=cfg).status is PlanStatus.SOLVED
        ticks = itertools.count(0.0, 100.0)  # a CPU clock that jumps 100 s per reading
        with monkeypatch.context() as m:
            m.setattr(time, "process_time", lambda: next(ticks))
            cpu = plan(dom, objs, state, goal, config=cfg)
            assert cpu.status is PlanStatus.TIME_LIMIT, engine
            wall = PlannerConfig(time_limit=5.0, engine=engine)
            assert plan(dom, objs, state, goal, config=wall).status is PlanStatus.SOLVED
    with pytest.raises(UsageError, match="'wall' or 'cpu'"):
        plan(dom, objs, state, goal, config=PlannerConfig(clock="sundial"))


def _chain_problem():
    ops = (_op("ab", [atom("a", x)], [atom("b", x)]), _op("bc", [atom("b", x)], [atom("c", x)]))
    dom = Domain("t", PREDS, ops, types={"o": None})
    return dom, {"k": "o"}, State([atom("a", "k")]), Goal.of([atom("c", "k")])
