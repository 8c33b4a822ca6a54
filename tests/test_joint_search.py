"""The searches below RCHPN's combined steps: no rewrites of held facts, one node budget per call.

``PlannerConfig.held_rewrites=False`` leaves out the successors that trade facts that hold for
other facts that hold through a zero-cost operator (on marsupial, a held ``same_city(p, v)``
regressed into the ``at(p, l)`` it is inferred from): A* met every subset of such facts
rewritten.  ``PlannerConfig.call_nodes`` bounds a call's expansions over all its attempts.
"""

from __future__ import annotations

from typing import Any

import pytest

from nowplan.acting.hpn import Frame
from nowplan.acting.peephole import Peephole, PeepholeConfig
from nowplan.core.atoms import Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.planning.plan import Plan, PlanStatus, PlanStep
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search
from tests.helpers import replay

pytestmark = pytest.mark.timeout(120)

o, p, q, lc = Var("o"), Var("p"), Var("q"), Var("l")

# A robot walks a line of rooms (seeing each) and may push objects along; ``ok(o)`` is inferred
# (cost 0) from an object lying anywhere.
OPS = (
    Operator("walk", (p, q), (Precondition(atom("robot_at", p), 1), Precondition(atom("next", p, q), 1)),
             (atom("robot_at", q), atom("robot_at", p, value=False), atom("seen", q)), cost=3.0),
    Operator("infer", (o, lc), (Precondition(atom("obj_at", o, lc), 1),), (atom("ok", o),), cost=0.0),
    Operator("push", (o, p, q), (Precondition(atom("robot_at", p), 1), Precondition(atom("obj_at", o, p), 1),
                                 Precondition(atom("next", p, q), 1)),
             (atom("robot_at", q), atom("robot_at", p, value=False), atom("obj_at", o, q),
              atom("obj_at", o, p, value=False)), cost=5.0),
)
PREDS = {n: Predicate(n, k) for n, k in [("robot_at", 1), ("next", 2), ("obj_at", 2), ("ok", 1), ("seen", 1)]}


def _one_place(x: Any, y: Any) -> bool:
    if x.value is not True or y.value is not True or x.predicate != y.predicate:
        return False
    if x.predicate == "robot_at":
        return bool(x.args != y.args)
    return x.predicate == "obj_at" and x.args[0] == y.args[0] and x.args[1] != y.args[1]


DOM = Domain("toy-line", PREDS, OPS, conflicts=(_one_place,))
ROOMS = ("r0", "r1", "r2", "r3", "r4")
OBJS = tuple(f"o{i}" for i in range(4))
OBJECTS = {**{r: "room" for r in ROOMS}, **{x: "obj" for x in OBJS}}


def _state() -> State:
    facts = [atom("robot_at", "r0")]
    facts += [atom("next", a, b) for a, b in zip(ROOMS, ROOMS[1:])]
    facts += [atom("next", b, a) for a, b in zip(ROOMS, ROOMS[1:])]
    facts += [atom("obj_at", x, "r1") for x in OBJS] + [atom("ok", x) for x in OBJS]
    return State(facts)


# there and back: the delete relaxation sees half the walk, so A* meets every subgoal below the cost
GOAL = Goal.of([atom("seen", "r4"), atom("robot_at", "r0"), *(atom("ok", x) for x in OBJS)])


def _config(**kw: Any) -> PlannerConfig:
    return PlannerConfig(engine="regression", heuristic="lmcut", lazy_relaxation=True, serialization=False,
                         monotonic=False, **kw)


def test_held_rewrites_off_keeps_the_plan_and_cuts_the_plateau() -> None:
    s = _state()
    on = plan(DOM, OBJECTS, s, GOAL, LevelMap(DOM.top_level), _config())
    off = plan(DOM, OBJECTS, s, GOAL, LevelMap(DOM.top_level), _config(held_rewrites=False))
    assert on.status is off.status is PlanStatus.SOLVED and on.plan is not None and off.plan is not None
    assert [a.name for a in off.plan.actions] == ["walk"] * 8
    assert sum(a.cost(s) for a in off.plan.actions) == sum(a.cost(s) for a in on.plan.actions)
    replay(DOM, s, off.plan)
    # with the rewrites every subset of the held ok(o) is a subgoal of its own (1108 against 280)
    assert on.expanded >= 2 * off.expanded


def test_pure_rewrite_names_a_new_held_fact() -> None:
    s = _state()
    search = _Search(DOM, OBJECTS, s, LevelMap(DOM.top_level), _config(), None)
    T = DOM.facts
    ok0, at0 = T.id(atom("ok", "o0")), T.id(atom("obj_at", "o0", "r1"))
    far = T.id(atom("robot_at", "r4"))  # does not hold
    away = T.id(atom("obj_at", "o0", "r3"))  # does not hold
    assert search.pure_rewrite(frozenset({ok0, far}), frozenset({at0, far}))
    # a child that only drops held facts is weaker than its parent: kept
    assert not search.pure_rewrite(frozenset({ok0, at0, far}), frozenset({at0, far}))
    # a child that asks for a fact that does not hold changes the unmet facts: kept
    assert not search.pure_rewrite(frozenset({ok0, far}), frozenset({away, far}))
    # trading an unmet fact is progress, not a rewrite
    assert not search.pure_rewrite(frozenset({far, ok0}), frozenset({T.id(atom("robot_at", "r3")), ok0}))


def test_call_nodes_bounds_the_attempts_together() -> None:
    s = _state()
    goal = Goal.of([atom("seen", "r4"), atom("robot_at", "r0"), atom("obj_at", "o0", "r3")])
    cfg = PlannerConfig(engine="regression", heuristic="count", shortcut_nodes=6, max_nodes=6)
    apart = plan(DOM, OBJECTS, s, goal, LevelMap(DOM.top_level), cfg)
    together = plan(DOM, OBJECTS, s, goal, LevelMap(DOM.top_level), PlannerConfig(
        engine="regression", heuristic="count", shortcut_nodes=6, max_nodes=6, call_nodes=8))
    assert apart.status is not PlanStatus.SOLVED and together.status is not PlanStatus.SOLVED
    assert apart.expanded > 8
    assert together.expanded <= 8 + 1  # an attempt counts the expansion that finds its budget spent
    assert together.status is PlanStatus.NODE_LIMIT


def test_call_nodes_leaves_solvable_calls_alone() -> None:
    s = _state()
    free = plan(DOM, OBJECTS, s, GOAL, LevelMap(DOM.top_level), _config(held_rewrites=False))
    bounded = plan(DOM, OBJECTS, s, GOAL, LevelMap(DOM.top_level), _config(held_rewrites=False, call_nodes=500))
    assert free.plan is not None and bounded.plan is not None
    assert free.plan.actions == bounded.plan.actions and free.expanded == bounded.expanded


def _frame(info: dict[str, Any], i: int = 1) -> Frame:
    steps = (PlanStep(None, GOAL), PlanStep(OPS[0].instantiate({p: "r0", q: "r1"}), GOAL))
    f = Frame(Plan(steps, LevelMap(DOM.top_level)), 1, 0, 0, i=i)
    f.info.update(info)
    return f


def test_peephole_bounds_searches_below_a_combined_step_only() -> None:
    base = PlannerConfig(max_nodes=50_000, shortcut_nodes=20_000)
    m = Peephole(PeepholeConfig(joint_nodes=300))
    ops = frozenset({("walk", ("r0", "r1")), ("walk", ("r1", "r2"))})
    joint = m.planner_config(None, _frame({"joint": 1, "joint_ops": ops}), GOAL, base)  # type: ignore[arg-type]
    assert joint is not None
    assert (joint.max_nodes, joint.shortcut_nodes, joint.call_nodes) == (300, 300, 300)
    assert not joint.held_rewrites and not joint.serialization
    below = m.planner_config(None, _frame({"under_joint": ops}), GOAL, base)  # type: ignore[arg-type]
    assert below is not None and below.call_nodes == 300 and not below.held_rewrites and below.serialization
    assert m.planner_config(None, _frame({}), GOAL, base) is None  # type: ignore[arg-type]
    keep = Peephole(PeepholeConfig(joint_nodes=300, held_rewrites=True))
    kept = keep.planner_config(None, _frame({"under_joint": ops}), GOAL, base)  # type: ignore[arg-type]
    assert kept is not None and kept.held_rewrites
