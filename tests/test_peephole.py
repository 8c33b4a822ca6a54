"""RCHPN's arrange rules, SelectGap and SelectParallelOps on hand-made subgoals and plans."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.acting.arrange import Arrange, Subgoal, arrange, depends, nothing_goes_first
from nowplan.acting.metrics import Outcome
from nowplan.acting.peephole import Peephole, PeepholeConfig
from nowplan.acting.reorder import Reorderer, highest_applicable
from nowplan.acting.resources import Estimator, ResourceModel
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.core.atoms import Atom, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Operator, Precondition, Resource, ResourceUse
from nowplan.core.state import State
from nowplan.domains.logistics import episode

o, lc, a, b = Var("o"), Var("l"), Var("a"), Var("b")
SH, CT, CN = ResourceUse.SHAREABLE, ResourceUse.CONTAINED, ResourceUse.CONTINUAL

# A robot puts objects in a room (using the doorway while it does), carries
# objects (using only itself) and closes the door (using the doorway for good).
OPS = (
    Operator("goto", (a, b), (Precondition(atom("robot_at", a), 2), Precondition(atom("link", a, b), 2)),
             (atom("robot_at", b), atom("robot_at", a, value=False)), cost=3.0),
    Operator("place", (o, lc), (Precondition(atom("obj_at", o, lc), 2), Precondition(atom("robot_at", lc), 1)),
             (atom("inside", o), atom("obj_at", o, lc, value=False)), cost=1.0,
             resources=(Resource(("robot",), SH), Resource(("doorway",), CT))),
    Operator("carry", (o, lc), (Precondition(atom("obj_at", o, lc), 2), Precondition(atom("robot_at", lc), 1)),
             (atom("carried", o), atom("obj_at", o, lc, value=False)), cost=1.0,
             resources=(Resource(("robot",), SH),)),
    Operator("close", (), (Precondition(atom("robot_at", "door"), 1),), (atom("closed"),), cost=1.0,
             resources=(Resource(("doorway",), CN),)),
    Operator("grab", (o,), (Precondition(atom("obj_at", o, "shelf"), 2),),
             (atom("have", o), atom("obj_at", o, "shelf", value=False)), cost=1.0),
    Operator("stow", (o,), (Precondition(atom("have", o), 2), Precondition(atom("robot_at", "door"), 1)),
             (atom("inside", o), atom("have", o, value=False)), cost=1.0,
             resources=(Resource(("doorway",), CT),)),
)


def one_place(x: Atom, y: Atom) -> bool:
    return x.predicate == y.predicate == "robot_at" and x.value is True and y.value is True and x.args != y.args


PREDS = {n: Predicate(n, k) for n, k in [("robot_at", 1), ("link", 2), ("obj_at", 2), ("inside", 1),
                                          ("carried", 1), ("closed", 0), ("have", 1)]}
TOY = Domain("toy-rooms", PREDS, OPS, conflicts=(one_place,))
PLACES = ("door", "hall", "yard", "shelf")
OBJECTS = {**{p: "loc" for p in PLACES}, **{x: "obj" for x in ("x", "y", "z", "w", "v")}}


def state(robot: str = "hall", **where: str) -> State:
    facts = [atom("robot_at", robot)]
    links = [("door", "hall"), ("hall", "yard"), ("hall", "shelf")]
    facts += [atom("link", p, q) for p, q in links] + [atom("link", q, p) for p, q in links]
    facts += [atom("obj_at", obj, place) for obj, place in where.items()]
    return State(facts)


def act(name: str, *args: str):
    op = next(x for x in OPS if x.name == name)
    return op.instantiate(dict(zip(op.params, args, strict=True)))


def reorderer(s: State, model: ResourceModel | None = None, **cfg: int) -> Reorderer:
    return Reorderer(TOY, OBJECTS, s, LevelMap(TOY.top_level), model or ResourceModel(), PeepholeConfig(**cfg))


def arr(s1, s2, s: State, model: ResourceModel | None = None) -> Arrange:
    model = model or ResourceModel(orders={"place": 1, "carry": 1, "close": 1, "stow": 1})
    est = Estimator(TOY, OBJECTS, s, model)
    sg1, sg2 = Subgoal(tuple(s1), Goal()), Subgoal(tuple(s2), Goal())
    return arrange(sg1, sg2, s, domain=TOY, levels=LevelMap(TOY.top_level), estimator=est)


# ------------------------------------------------------------------ arrange rules


def test_only_shareable_resources_in_common_combine():
    s = state(x="yard", y="yard")
    assert arr([act("carry", "x", "yard")], [act("carry", "y", "yard")], s) is Arrange.COMBINE


def test_contained_before_continual_either_way_round():
    s = state(x="hall")
    assert arr([act("close")], [act("place", "x", "hall")], s) is Arrange.SECOND
    assert arr([act("place", "x", "hall")], [act("close")], s) is Arrange.FIRST


def test_all_contained_any_order_easier_first():
    # both use the doorway (contained): the one reachable with less effort goes first
    s = state(robot="hall", x="yard", y="hall")
    assert arr([act("place", "x", "yard")], [act("place", "y", "hall")], s) is Arrange.SECOND
    assert arr([act("place", "y", "hall")], [act("place", "x", "yard")], s) is Arrange.FIRST


def test_nothing_in_common_keeps_the_order():
    s = state(x="yard")
    assert arr([act("carry", "x", "yard")], [act("close")], s) is Arrange.FIRST


def test_a_step_needing_the_other_is_not_combined_or_moved():
    s = state(x="shelf")
    first, second = [act("grab", "x")], [act("stow", "x")]
    assert depends(TOY, first, second) and not depends(TOY, second, first)
    assert arr(second, first, s) is Arrange.FIRST


def test_domain_can_refuse_to_share_and_can_declare_clashes():
    s = state(robot="yard", x="yard", y="hall")
    no_share = ResourceModel(orders={"carry": 1}, shareable=lambda r, s1, s2, bel: False)
    # not shareable after all: a serialization, the easier (x: robot already there) first
    assert arr([act("carry", "y", "hall")], [act("carry", "x", "yard")], s, no_share) is Arrange.SECOND
    clash = ResourceModel(clash=lambda r1, r2: {r1, r2} == {("robot",), ("doorway",)})
    assert arr([act("carry", "x", "yard")], [act("close")], s, clash) is Arrange.FIRST
    assert arr([act("close")], [act("carry", "x", "yard")], s, clash) is Arrange.SECOND


def test_estimate_orders_add_hidden_preconditions_resources():
    s = state(robot="yard", x="hall")
    levels = LevelMap(TOY.top_level)
    zeroth = Estimator(TOY, OBJECTS, s, ResourceModel()).estimate(act("place", "x", "hall"), levels)
    first = Estimator(TOY, OBJECTS, s, ResourceModel(orders={"place": 1})).estimate(
        act("place", "x", "hall"), levels)
    assert set(zeroth.uses) == {("robot",), ("doorway",)}
    assert zeroth.effort == 0.0 and first.effort == 3.0  # one goto to reach the hall


# ------------------------------------------------------------------ SelectGap / SelectParallelOps


def test_select_gap_moves_the_contained_step_before_the_continual_one():
    s = state(robot="door", x="hall")
    r = reorderer(s)
    ops = [act("close"), act("place", "x", "hall")]
    goal = Goal.of([atom("closed"), atom("inside", "x")])
    ops, goals = r.chain(ops, goal)
    assert TOY.satisfies(s, goals[0])
    new, new_goals = r.select_gap(ops, goals)
    assert [str(x) for x in new] == ["place(x, hall)", "close()"]
    assert (new, new_goals) == r.valid(new, goal) and len(r.moves) == 1


def test_select_gap_does_not_move_when_the_result_is_invalid():
    s = state(robot="door", x="shelf")
    r = reorderer(s)
    ops = [act("close"), act("grab", "x"), act("stow", "x")]  # stow needs the grab before it
    goal = Goal.of([atom("closed"), atom("inside", "x")])
    ops, goals = r.chain(ops, goal)
    assert r.arrange(Subgoal((ops[0],), goals[1]), Subgoal((ops[2],), goals[3])) is Arrange.SECOND
    new, _ = r.select_gap(list(ops), goals)
    # refused before the validity check: stow's have(x) holds neither now nor after nothing
    assert new == ops and not r.moves and not r.can_follow(ops[2], ())
    assert r.valid([ops[2], ops[0], ops[1]], goal) is None
    # once the object is held, the same preference may be followed
    s2 = State([*state(robot="door").atoms(), atom("have", "x")])
    r2 = reorderer(s2)
    ops2 = [act("close"), act("stow", "x")]
    new2, _ = r2.select_gap(*r2.chain(ops2, goal))
    assert [str(x) for x in new2] == ["stow(x)", "close()"]


def test_select_gap_terminates_on_a_cyclic_preference():
    s = state(x="hall", y="hall", z="hall")
    always_second = ResourceModel(arrange=lambda s1, s2, bel, **kw: Arrange.SECOND)
    r = reorderer(s, always_second, max_moves=7)
    ops = [act("carry", "x", "hall"), act("carry", "y", "hall"), act("carry", "z", "hall")]
    goal = Goal.of([atom("carried", q) for q in "xyz"])
    new, goals = r.select_gap(*r.chain(ops, goal))
    assert len(r.moves) == 7 and sorted(map(str, new)) == sorted(map(str, ops))
    assert r.valid(new, goal) == (new, goals)


def test_select_parallel_ops_combines_up_to_the_complexity_limit():
    s = state(robot="yard", x="yard", y="hall", z="yard", w="yard")
    r = reorderer(s, ResourceModel(), max_combined=3, min_hidden_to_combine=1)
    ops = [act("carry", "x", "yard"), act("close"), act("carry", "y", "hall"),
           act("carry", "z", "yard"), act("carry", "w", "yard")]
    goal = Goal.of([atom("closed"), *(atom("carried", q) for q in "xyzw")])
    ops, goals = r.chain(ops, goal)
    new, new_goals, last = r.select_parallel_ops(ops, goals)
    assert last == 2  # three operators in the combined subgoal
    assert [x.name for x in new[:3]] == ["carry"] * 3 and str(new[3]) == "close()"
    assert (new, new_goals) == r.valid(new, goal)
    combined = new_goals[last + 1]
    assert all(atom("carried", x.args[0]) in combined.atoms for x in new[:3])


def test_steps_in_their_last_refinement_are_not_combined():
    s = state(robot="yard", x="yard", z="yard")
    r = reorderer(s, ResourceModel())  # default: two hidden criticality classes needed
    ops, goals = r.chain([act("carry", "x", "yard"), act("carry", "z", "yard")],
                         Goal.of([atom("carried", "x"), atom("carried", "z")]))
    s1, s2 = Subgoal((ops[0],), goals[1]), Subgoal((ops[1],), goals[2])
    assert arr([ops[0]], [ops[1]], s, ResourceModel()) is Arrange.COMBINE  # the rules alone would combine
    assert r.arrange(s1, s2) is Arrange.FIRST  # but nothing is left to share: equally easy, keep the order
    assert r.select_parallel_ops(ops, goals)[2] == 0


def test_validity_drops_a_redundant_step_that_would_break_the_chain():
    # carry(x) achieves nothing the goal needs and would undo obj_at(x, hall): it is dropped
    s = state(robot="hall", x="hall", y="hall")
    r = reorderer(s)
    goal = Goal.of([atom("obj_at", "x", "hall"), atom("carried", "y")])
    kept, goals = r.valid([act("carry", "y", "hall"), act("carry", "x", "hall")], goal)
    assert [str(a) for a in kept] == ["carry(y, hall)"] and goals[-1] == goal
    # a useful step whose regression fails still makes the plan invalid
    assert r.valid([act("carry", "x", "hall")], Goal.of([atom("obj_at", "x", "hall"), atom("carried", "x")])) is None


def test_select_parallel_ops_skips_a_combination_that_breaks_the_plan():
    s = state(robot="hall", x="hall", y="shelf", z="hall")
    r = reorderer(s, ResourceModel(arrange=lambda s1, s2, bel, **kw: Arrange.COMBINE), min_hidden_to_combine=1)
    # stow(y) needs the grab before it, so it cannot join carry(x); carry(z) can
    ops = [act("carry", "x", "hall"), act("grab", "y"), act("stow", "y"), act("carry", "z", "hall")]
    goal = Goal.of([atom("carried", "x"), atom("carried", "z"), atom("inside", "y")])
    ops, goals = r.chain(ops, goal)
    new, new_goals, last = r.select_parallel_ops(list(ops), goals)
    assert last == 1
    assert [str(x) for x in new] == ["carry(x, hall)", "carry(z, hall)", "grab(y)", "stow(y)"]
    assert (new, new_goals) == r.valid(new, goal)


def test_highest_applicable_subgoal():
    from nowplan.planning.plan import Plan, PlanStep

    s = state(robot="hall", x="hall")
    r = reorderer(s)
    ops = [act("goto", "door", "hall"), act("place", "x", "hall")]
    ops, goals = r.chain(ops, Goal.of([atom("inside", "x")]))
    p = Plan(tuple([PlanStep(None, goals[0]), *(PlanStep(op, g) for op, g in zip(ops, goals[1:]))]),
             LevelMap(TOY.top_level))
    assert highest_applicable(TOY, s, p) == 1  # the robot is already in the hall


def toy_errand_plan() -> tuple[list[Any], Any]:
    """Seven toy steps (place x in the hall, carry y, close) chained from the door, and their plan."""
    from nowplan.planning.plan import Plan, PlanStep

    s = state(robot="door", x="hall", y="yard")
    ops = [act("goto", "door", "hall"), act("place", "x", "hall"), act("goto", "hall", "yard"),
           act("carry", "y", "yard"), act("goto", "yard", "hall"), act("goto", "hall", "door"), act("close")]
    ops, goals = reorderer(s).chain(ops, Goal.of([atom("inside", "x"), atom("carried", "y"), atom("closed")]))
    return ops, Plan(tuple([PlanStep(None, goals[0]), *(PlanStep(op, g) for op, g in zip(ops, goals[1:]))]),
                     LevelMap(TOY.top_level))


@settings(max_examples=100, deadline=None)
@given(st.data())
def test_highest_applicable_with_watched_atoms_answers_as_without(data: st.DataObject) -> None:
    """The watched atoms kept for a plan across beliefs change no answer, whatever the beliefs."""
    ops, p = toy_errand_plan()
    watch: dict = {}
    for _ in range(data.draw(st.integers(1, 8))):
        here = data.draw(st.sampled_from(PLACES))
        facts = list(state(robot=here, x=data.draw(st.sampled_from(PLACES)),
                           y=data.draw(st.sampled_from(PLACES))).atoms())
        facts += [atom(n, *args) for n, args in data.draw(st.lists(st.sampled_from(
            [("inside", ("x",)), ("carried", ("y",)), ("closed", ())]), unique=True))]
        b = State(facts)
        assert highest_applicable(TOY, b, p, watch) == highest_applicable(TOY, b, p)


# ------------------------------------------------------------------ whole runs


def test_peephole_switch_is_registered():
    st = parse_strategy("hpn+peephole")
    assert any(isinstance(m, Peephole) for m in st.mechanisms())


@pytest.mark.parametrize("seed", [0, 1])
def test_rchpn_on_logistics_reaches_the_goal_with_valid_actions(seed):
    ep = episode("medium", seed)
    world = ep.world
    ran_ok: list[bool] = []
    orig = world.execute

    def checked(action):
        ran_ok.append(world.applicable(action))
        return orig(action)

    world.execute = checked
    m = run_episode(ep, parse_strategy("hpn+peephole"), seed=seed)
    assert m.outcome is Outcome.REACHED, m.reason
    assert ran_ok and all(ran_ok)
    assert ep.problem.domain.satisfies(world.state, ep.problem.goal)


def test_select_parallel_ops_does_not_form_a_combination_that_failed():
    s = state(robot="yard", x="yard", y="hall", z="yard", w="yard")
    ops = [act("carry", "x", "yard"), act("close"), act("carry", "y", "hall"),
           act("carry", "z", "yard"), act("carry", "w", "yard")]
    goal = Goal.of([atom("closed"), *(atom("carried", q) for q in "xyzw")])
    failed = frozenset({act("carry", "x", "yard").key, act("carry", "y", "hall").key})
    r = Reorderer(TOY, OBJECTS, s, LevelMap(TOY.top_level), ResourceModel(),
                  PeepholeConfig(max_combined=3, min_hidden_to_combine=1), failed=[failed])
    new, _, last = r.select_parallel_ops(*r.chain(ops, goal))
    assert last == 2
    assert {str(a) for a in new[:3]} == {"carry(x, yard)", "carry(z, yard)", "carry(w, yard)"}


def test_peephole_remembers_a_failed_combination_until_the_next_action():
    from types import SimpleNamespace

    from nowplan.acting.peephole import Peephole
    from nowplan.planning.plan import PlanResult, PlanStatus
    from nowplan.trace import Trace

    m = Peephole()
    ex = SimpleNamespace(metrics=SimpleNamespace(actions=3), trace=Trace())
    combo = frozenset({("carry", ("x", "yard")), ("carry", ("y", "hall"))})
    parent = SimpleNamespace(plan_id=7, i=2, info={"joint": 2, "joint_ops": combo})
    m.after_plan_failure(ex, parent, Goal(), PlanResult(PlanStatus.UNSOLVABLE, reason="exhausted"))
    assert m._failed == [combo] and m._failed_at == 3
    assert "not combined again" in ex.trace.of("note")[0]["text"]
    # a failure of an ordinary (uncombined) step is not recorded
    plain = SimpleNamespace(plan_id=8, i=1, info={"joint": None, "joint_ops": None})
    m.after_plan_failure(ex, plain, Goal(), PlanResult(PlanStatus.UNSOLVABLE, reason="exhausted"))
    assert m._failed == [combo]


def test_a_combination_too_large_to_plan_lowers_the_complexity_limit_until_the_next_action():
    from types import SimpleNamespace

    from nowplan.acting.peephole import Peephole
    from nowplan.planning.plan import PlanResult, PlanStatus
    from nowplan.trace import Trace

    m = Peephole(PeepholeConfig(max_combined=4))
    ex = SimpleNamespace(metrics=SimpleNamespace(actions=5), trace=Trace())

    def fail(n: int, status: PlanStatus) -> None:
        combo = frozenset(("carry", (f"q{i}", "yard")) for i in range(n))
        parent = SimpleNamespace(plan_id=1, i=1, info={"joint": 1, "joint_ops": combo})
        m.after_plan_failure(ex, parent, Goal(), PlanResult(status, reason="r"))

    fail(4, PlanStatus.TIME_LIMIT)
    assert m._cap == 3 and "nor more than 3 steps" in ex.trace.of("note")[-1]["text"]
    fail(3, PlanStatus.UNSOLVABLE)  # a combination proved impossible is remembered, the limit kept
    assert m._cap == 3
    fail(3, PlanStatus.NODE_LIMIT)
    fail(2, PlanStatus.TIME_LIMIT)
    assert m._cap == 1  # one step at a time, as HPN
    ex.metrics.actions = 6  # the belief changed: the paper's limit again
    assert m._failed_now(ex) == [] and m._cap == 4


def test_refinements_of_a_combined_step_inherit_it_bound_their_searches_and_report_failures():
    from types import SimpleNamespace

    from nowplan.acting.peephole import Peephole
    from nowplan.planning.plan import PlanResult, PlanStatus
    from nowplan.planning.regression import PlannerConfig
    from nowplan.trace import Trace

    m = Peephole(PeepholeConfig(joint_nodes=500))
    ex = SimpleNamespace(metrics=SimpleNamespace(actions=2), trace=Trace(), stack=[])
    combo = frozenset({("carry", ("x", "yard")), ("carry", ("z", "yard"))})
    plan = SimpleNamespace(steps=(None, None, None))
    top = SimpleNamespace(plan_id=1, i=2, info={"joint": 2, "joint_ops": combo}, plan=plan)
    child = SimpleNamespace(plan_id=2, i=1, info={}, plan=plan)
    grandchild = SimpleNamespace(plan_id=3, i=1, info={}, plan=plan)
    for fr in (top, child, grandchild):
        ex.stack.append(fr)
        m.after_push(ex, fr)
    assert "under_joint" not in top.info  # pushed at the root of the stack
    assert child.info["under_joint"] == combo and grandchild.info["under_joint"] == combo
    base = PlannerConfig(max_nodes=50_000, shortcut_nodes=20_000)
    joint = m.planner_config(ex, top, Goal(), base)
    assert joint is not None and not joint.serialization and joint.max_nodes == 500 and joint.shortcut_nodes == 500
    below = m.planner_config(ex, grandchild, Goal(), base)
    assert below is not None and below.serialization and below.max_nodes == 500
    # a step not under any combination keeps the planner's budgets
    plain = SimpleNamespace(plan_id=9, i=1, info={"joint": None}, plan=plan)
    assert m.planner_config(ex, plain, Goal(), base) is None
    # a refinement below the combined step that fails gives the combination up in this belief
    m.after_plan_failure(ex, grandchild, Goal(), PlanResult(PlanStatus.NODE_LIMIT, reason="budget"))
    assert m._failed == [combo] and m._cap == 1


def test_without_a_node_budget_below_combined_steps_the_planners_budgets_apply():
    from types import SimpleNamespace

    from nowplan.acting.peephole import Peephole
    from nowplan.planning.regression import PlannerConfig

    m = Peephole(PeepholeConfig(joint_nodes=0))
    combo = frozenset({("carry", ("x", "yard"))})
    parent = SimpleNamespace(plan_id=1, i=2, info={"under_joint": combo})
    out = m.planner_config(SimpleNamespace(), parent, Goal(), PlannerConfig())
    base = PlannerConfig()
    # only the held rewrites are left out (PeepholeConfig.held_rewrites, tests/test_joint_search.py)
    assert out is not None and not out.held_rewrites
    assert (out.max_nodes, out.shortcut_nodes, out.call_nodes) == (base.max_nodes, base.shortcut_nodes, 0)
    plain = Peephole(PeepholeConfig(joint_nodes=0, held_rewrites=True))
    assert plain.planner_config(SimpleNamespace(), parent, Goal(), PlannerConfig()) is None


def test_estimates_can_use_the_executives_planner_settings():
    from nowplan.acting.reorder import estimate_config
    from nowplan.planning.regression import PlannerConfig

    cfg = estimate_config(PlannerConfig(heuristic="lmcut", lazy_relaxation=True, max_nodes=9, improve=2.0), 300)
    assert cfg.heuristic == "lmcut" and cfg.lazy_relaxation and cfg.max_nodes == cfg.shortcut_nodes == 300
    assert cfg.serialization and not cfg.monotonic and cfg.improve == 0.0
    s = state(robot="yard", x="yard", y="hall", z="yard", w="yard")
    r = Reorderer(TOY, OBJECTS, s, LevelMap(TOY.top_level), ResourceModel(),
                  PeepholeConfig(estimate_search=None), planner=PlannerConfig(heuristic="hmax"))
    assert r.estimator.search.heuristic == "hmax" and r.estimator.search.max_nodes == 300
    assert Reorderer(TOY, OBJECTS, s, LevelMap(TOY.top_level)).estimator.search.heuristic == "hadd"


# ------------------------------------------------------------------ giving a combination up

def _toy_executive(s: State):
    from types import SimpleNamespace

    from nowplan.acting.strategy import parse_strategy
    from nowplan.trace import Trace

    problem = SimpleNamespace(objects=OBJECTS)
    return SimpleNamespace(domain=TOY, problem=problem, belief=s, strategy=parse_strategy("hpn+peephole"),
                           metrics=SimpleNamespace(actions=0), trace=Trace(), stack=[])


def _three_carries() -> tuple[Any, Any, LevelMap]:
    """The toy yard with three carries planned at the top level: (belief, plan, its level map)."""
    from nowplan.planning.plan import Plan, PlanStep

    s = state(robot="yard", x="yard", z="yard", w="yard")
    ops = [act("carry", "x", "yard"), act("carry", "z", "yard"), act("carry", "w", "yard")]
    goal = Goal.of([atom("carried", q) for q in "xzw"])
    own = LevelMap(TOY.top_level)
    kept, goals = Reorderer(TOY, OBJECTS, s, own).chain(ops, goal)
    return s, Plan((PlanStep(None, goals[0]), *(PlanStep(a, g) for a, g in zip(kept, goals[1:]))), own), own


def test_combined_operators_are_lowered_for_their_joint_refinement_only():
    from types import SimpleNamespace

    from nowplan.planning.plan import PlanResult, PlanStatus

    s, plan, own = _three_carries()
    m = Peephole(PeepholeConfig(max_combined=3, min_hidden_to_combine=1))
    ex = _toy_executive(s)
    frame = SimpleNamespace(plan=plan, plan_id=1, i=0, root=False, info={}, n=len(plan.steps))
    step = m.next_step(ex, frame)
    assert frame.info["joint"] == frame.i == 3 and step is frame.plan.steps[3]
    lowered = frame.plan.levels
    assert lowered != own and frame.info["own_levels"] == own  # Alg. 2 lines 11-13, for the joint subgoal
    # the joint subgoal had no plan: the next choice refines one step, from the plan's own levels
    # the joint subgoal ran out of nodes: two steps are combined, lowered from the plan's own levels
    # (not from the levels lowered for the three)
    m.after_plan_failure(ex, frame, plan.steps[-1].goal, PlanResult(PlanStatus.NODE_LIMIT, reason="budget"))
    frame.i = 0
    m.next_step(ex, frame)
    assert frame.info["joint"] == 2 and frame.plan.levels == own.next_level(frame.plan.steps[1].action)
    # that one too: the next choice refines one step, at the plan's own levels
    m.after_plan_failure(ex, frame, plan.steps[-1].goal, PlanResult(PlanStatus.NODE_LIMIT, reason="budget"))
    frame.i = 0
    m.next_step(ex, frame)
    assert frame.info["joint"] is None and frame.plan.levels == own and "own_levels" not in frame.info


def test_a_failure_below_a_combined_step_pops_the_plans_above_the_one_that_combined_them():
    from types import SimpleNamespace

    from nowplan.planning.plan import PlanResult, PlanStatus
    from nowplan.trace import Trace

    m = Peephole(PeepholeConfig(joint_nodes=500))
    ex = SimpleNamespace(metrics=SimpleNamespace(actions=2), trace=Trace(), stack=[])
    combo = frozenset({("carry", ("x", "yard")), ("carry", ("z", "yard"))})
    plan = SimpleNamespace(steps=(None, None, None))
    base = SimpleNamespace(plan_id=0, i=1, info={}, plan=plan, root=False, n=3)
    top = SimpleNamespace(plan_id=1, i=2, info={"joint": 2, "joint_ops": combo}, plan=plan, root=False, n=3)
    child = SimpleNamespace(plan_id=2, i=1, info={}, plan=plan, root=False, n=3)
    grandchild = SimpleNamespace(plan_id=3, i=1, info={}, plan=plan, root=False, n=3)
    for fr in (base, top, child, grandchild):
        ex.stack.append(fr)
        m.after_push(ex, fr)
    assert child.info["joint_owner"] == grandchild.info["joint_owner"] == 1
    # the joint subgoal itself has no plan: the executive's backtrack pops the plan that combined them
    m.after_plan_failure(ex, top, Goal(), PlanResult(PlanStatus.UNSOLVABLE, reason="exhausted"))
    assert m._unwind_to is None
    # a refinement two levels below fails: every plan above the combining one is popped
    m.after_plan_failure(ex, grandchild, Goal(), PlanResult(PlanStatus.NODE_LIMIT, reason="budget"))
    assert m._unwind_to == 1 and "plans above plan 1" in ex.trace.of("note")[-1]["text"]
    ex.stack.pop()  # the executive's backtrack pops the failing frame itself
    assert m.applicable(ex, child) is False
    ex.stack.pop()
    top.i = top.n  # (so that applicable() answers without a domain)
    m.applicable(ex, top)
    assert m._unwind_to is None  # reached the combining plan: it chooses again, without the combination


def _random_jobs(seed: int):
    """Four jobs with random resource uses, costs, domain tests and reachability (a random ``prep``
    operator makes a job's ``ready`` precondition true, or none does: effort inf)."""
    import random

    from nowplan.core.operators import Operator as Op

    rng = random.Random(seed)
    uses = (SH, CT, CN)
    names = [("robot",), ("doorway",), ("room", "a"), ("room", "b")]

    def random_op(k: int) -> Op:
        res = tuple(Resource(r, rng.choice(uses)) for r in rng.sample(names, rng.randint(0, 3)))
        return Op(f"job{k}", (), (Precondition(atom(f"ready{k}"), 1),), (atom(f"done{k}"),),
                  cost=float(rng.randint(1, 3)), resources=res)

    jobs = [random_op(k) for k in range(4)]
    helpers = tuple(Op(f"prep{k}", (), (), (atom(f"ready{k}"),), cost=float(rng.randint(0, 4)),
                       resources=tuple(Resource(r, rng.choice(uses)) for r in rng.sample(names, rng.randint(0, 2))))
                    for k in range(4) if rng.random() < 0.8)  # some jobs cannot be prepared: effort inf
    preds = {**{f"ready{k}": Predicate(f"ready{k}", 0) for k in range(4)},
             **{f"done{k}": Predicate(f"done{k}", 0) for k in range(4)}}
    dom = Domain("jobs", preds, (*jobs, *helpers))
    belief = State([atom(f"ready{k}") for k in range(4) if rng.random() < 0.3])
    table = {r: rng.choice([True, False, None]) for r in names}
    model = ResourceModel(orders={j.name: 1 for j in jobs}, shareable=lambda r, a, b, s: table[r])
    return rng, dom, belief, model, [j.instantiate({}) for j in jobs], helpers


@pytest.mark.parametrize("seed", range(40))
def test_arrange_asked_for_one_verdict_agrees_with_the_full_verdict(seed):
    """The cheap path of ``arrange(want=...)`` (no shareability test where it cannot matter) is
    conservative: it answers ``want`` exactly when the full rules do, on random resource uses,
    domain tests and reachability."""
    _, dom, belief, model, acts, _ = _random_jobs(seed)
    levels = LevelMap(1)
    for i in range(4):
        for j in range(4):
            if i == j:
                continue
            est = Estimator(dom, {}, belief, model)
            s1, s2 = Subgoal((acts[i],), Goal()), Subgoal((acts[j],), Goal())
            full = arrange(s1, s2, belief, domain=dom, levels=levels, estimator=est, model=model)
            for want in (Arrange.SECOND, Arrange.COMBINE):
                quick = arrange(s1, s2, belief, domain=dom, levels=levels, estimator=est, model=model, want=want)
                assert (quick is want) == (full is want), (i, j, want, full, quick)


@pytest.mark.parametrize("seed", range(40))
def test_arrange_with_an_effort_bound_agrees_with_the_full_verdict(seed):
    """With a domain's admissible effort bound (random, from 0 up to the true cost; anything for a
    job no plan prepares), ``arrange(want=SECOND)`` asked first, in a fresh belief's estimator, so
    that the bound is what it sees of the second step, answers SECOND exactly when the full rules
    do."""
    rng, dom, belief, model, acts, helpers = _random_jobs(seed)
    cost = {h.name.removeprefix("prep"): float(h.cost) for h in helpers}  # type: ignore[arg-type]
    factor = {k: rng.random() for k in "0123"}

    def bound(unmet, s):
        ks = [x.predicate.removeprefix("ready") for x in unmet]
        return max(cost[k] * factor[k] if k in cost else 10.0 * factor[k] for k in ks)

    bounded = replace(model, effort_bound=bound)
    levels = LevelMap(1)
    for i in range(4):
        for j in range(4):
            if i == j:
                continue
            s1, s2 = Subgoal((acts[i],), Goal()), Subgoal((acts[j],), Goal())
            full = arrange(s1, s2, belief, domain=dom, levels=levels, estimator=Estimator(dom, {}, belief, model),
                           model=model)
            est = Estimator(dom, {}, belief, bounded)
            quick = arrange(s1, s2, belief, domain=dom, levels=levels, estimator=est, model=bounded,
                            want=Arrange.SECOND)
            assert (quick is Arrange.SECOND) == (full is Arrange.SECOND), (i, j, full, quick)


def test_an_effort_bound_spares_the_second_steps_small_search():
    """SelectGap's question "does the second go first?" needs no small plan for the second step
    when its effort bound already reaches the first's effort and the first uses nothing
    continually (Estimator.effort_bound); the answer is the full rules' one."""
    s = state(robot="hall", x="yard", y="yard")  # both carries need the robot walked to the yard
    plain = ResourceModel(orders={"carry": 1})
    lv = LevelMap(TOY.top_level)
    s1 = Subgoal((act("carry", "x", "yard"),), Goal())
    s2 = Subgoal((act("carry", "y", "yard"),), Goal())
    est = Estimator(TOY, OBJECTS, s, plain)
    full = arrange(s1, s2, s, domain=TOY, levels=lv, estimator=est)
    # both steps' small plans asked (the second one answered by the first's search: the same
    # unmet robot_at(yard), Estimator._by_goal)
    assert full is not Arrange.SECOND and len(est._plans) == 2 and est.plan_calls == 1
    est = Estimator(TOY, OBJECTS, s, plain)
    assert est.effort_bound(act("carry", "y", "yard"), lv) == 3.0  # goto, the cheapest achiever of robot_at
    assert arrange(s1, s2, s, domain=TOY, levels=lv, estimator=est, want=Arrange.SECOND) is not Arrange.SECOND
    assert len(est._plans) == 1  # only the first step's small plan (one goto: effort 3 = the bound)
    # with a lower bound than the first's effort, the second's small search is made as before
    cheap = replace(plain, effort_bound=lambda unmet, belief: 0.0)
    est = Estimator(TOY, OBJECTS, state(robot="hall", x="yard", y="yard"), cheap)
    est._cheapest["robot_at"] = 0.0  # as for a domain whose operators' costs are not known
    arrange(s1, s2, s, domain=TOY, levels=lv, estimator=est, model=cheap, want=Arrange.SECOND)
    assert len(est._plans) == 2


def test_arrange_asked_for_second_skips_the_domains_test_when_it_cannot_matter():
    calls: list[object] = []

    def test(r, a, b, s):
        calls.append(r)
        return True

    model = ResourceModel(orders={"place": 1, "carry": 1}, shareable=test)
    s = state(robot="yard", x="yard", y="yard")
    est = Estimator(TOY, OBJECTS, s, model)
    s1 = Subgoal((act("carry", "x", "yard"),), Goal())
    s2 = Subgoal((act("carry", "y", "yard"),), Goal())
    lv = LevelMap(TOY.top_level)
    # both only share the robot, both as easy: SECOND is impossible whatever the test says
    assert arrange(s1, s2, s, domain=TOY, levels=lv, estimator=est, model=model, want=Arrange.SECOND) is not Arrange.SECOND
    assert calls == []
    assert arrange(s1, s2, s, domain=TOY, levels=lv, estimator=est, model=model) is Arrange.COMBINE
    assert calls == [("robot",)]


def test_revalidating_a_reordered_plan_regresses_only_its_new_head():
    s = state(robot="yard", x="yard", y="hall", z="yard", w="yard")
    r = reorderer(s)
    ops = [act("carry", "x", "yard"), act("close"), act("carry", "y", "hall"),
           act("carry", "z", "yard"), act("carry", "w", "yard")]
    goal = Goal.of([atom("closed"), *(atom("carried", q) for q in "xyzw")])
    first = r.chain(ops, goal)
    assert first is not None and r.regressions == len(ops)
    again = r.chain(ops, goal)  # the same plan again: nothing regressed anew
    assert again == first and r.regressions == len(ops)
    moved = [ops[3], *ops[:3], ops[4]]  # carry z moved to the front: the tail (carry w) is shared
    got = r.chain(moved, goal)
    assert r.regressions == len(ops) + 4
    # the cached chain equals a fresh Reorderer's, with or without the move
    fresh = reorderer(s)
    assert got == fresh.chain(moved, goal) and first == fresh.chain(ops, goal)


def test_a_run_wide_preimage_table_serves_the_next_beliefs_reorderer():
    """Pre-images do not depend on the belief: a Reorderer of the next belief given the same table
    regresses nothing anew for the plan it validated before, and its chain equals a fresh one's."""
    ops = [act("carry", "x", "yard"), act("close"), act("carry", "y", "hall")]
    goal = Goal.of([atom("closed"), *(atom("carried", q) for q in "xy")])
    table: dict = {}
    lv = LevelMap(TOY.top_level)
    s1, s2 = state(robot="yard", x="yard", y="hall"), state(robot="hall", x="yard", y="hall")
    r1 = Reorderer(TOY, OBJECTS, s1, lv, ResourceModel(), PeepholeConfig(), regressed=table)
    first = r1.chain(ops, goal)
    assert first is not None and r1.regressions == len(ops)
    r2 = Reorderer(TOY, OBJECTS, s2, lv, ResourceModel(), PeepholeConfig(), regressed=table)
    assert r2.chain(ops, goal) == first == reorderer(s2).chain(ops, goal) and r2.regressions == 0
    # the table is keyed by the operator's level too: another level map regresses anew
    low = LevelMap(0)
    r3 = Reorderer(TOY, OBJECTS, s2, low, ResourceModel(), PeepholeConfig(), regressed=table)
    assert r3.chain(ops, goal) == Reorderer(TOY, OBJECTS, s2, low).chain(ops, goal) and r3.regressions > 0


@pytest.mark.parametrize("seed", range(40))
def test_nothing_goes_first_only_where_no_step_would_be_second(seed):
    """``nothing_goes_first(s1)`` (SelectGap then looks at no later step) holds only where
    ``arrange(s1, s2, want=SECOND)`` is not SECOND for every other ``s2``, on random resource uses,
    domain tests, reachability and efforts; and it holds for some of the random cases (the test
    would notice a condition that is never true)."""
    _, dom, belief, model, acts, _ = _random_jobs(seed)
    levels = LevelMap(1)
    for i in range(4):
        s1 = Subgoal((acts[i],), Goal())
        if not nothing_goes_first(s1, Estimator(dom, {}, belief, model), levels, model):
            continue
        NOTHING_FIRST_SEEN.append(seed)
        for j in range(4):
            if j != i:
                est = Estimator(dom, {}, belief, model)
                s2 = Subgoal((acts[j],), Goal())
                assert arrange(s1, s2, belief, domain=dom, levels=levels, estimator=est, model=model,
                               want=Arrange.SECOND) is not Arrange.SECOND, (i, j)
                r = Reorderer(dom, {}, belief, levels, model)
                assert r.arrange(s1, s2, Arrange.SECOND) is not Arrange.SECOND, (i, j)


NOTHING_FIRST_SEEN: list[int] = []


def test_nothing_goes_first_is_seen_on_the_random_jobs():
    for seed in range(40):
        test_nothing_goes_first_only_where_no_step_would_be_second(seed)
    assert NOTHING_FIRST_SEEN


def test_select_gap_skips_the_later_steps_of_a_first_step_with_nothing_to_wait_for():
    """SelectGap with a first step whose exposed preconditions hold (effort 0, nothing continual)
    asks ``arrange`` about no later step, and the plan is unchanged, as the full rules leave it."""
    s = state(robot="yard", x="yard", y="yard")
    ops = [act("carry", "x", "yard"), act("carry", "y", "yard")]
    goal = Goal.of([atom("carried", "x"), atom("carried", "y")])
    r = Reorderer(TOY, OBJECTS, s, LevelMap(TOY.top_level), ResourceModel(orders={"carry": 1}))
    chain = r.chain(ops, goal)
    assert chain is not None
    asked: list[object] = []
    own = r.arrange
    r.arrange = lambda s1, s2, want=None: asked.append(s2) or own(s1, s2, want)  # type: ignore[method-assign]
    out = r.select_gap(*chain)
    assert out[0] == ops and asked == [] and r.moves == []


# ------------------------------------------------------------------ gather (ours)


def _share_declared(s1, s2, bel, **kw) -> Arrange:
    """Combine exactly the subgoals whose operators declare a resource in common."""
    names = lambda sg: {r.name for a in sg.actions for r in a.resources()}  # noqa: E731
    return Arrange.COMBINE if names(s1) & names(s2) else Arrange.FIRST


def _gather_case(**cfg: int):
    from nowplan.acting.gather import gather

    s = state(robot="hall", x="hall", y="shelf")
    r = reorderer(s, ResourceModel(arrange=_share_declared), min_hidden_to_combine=1, **cfg)
    # stow(y) shares the doorway with place(x) but needs grab(y), still ahead: SelectParallelOps
    # cannot pull it next to place(x)
    goal = Goal.of([atom("inside", "x"), atom("inside", "y")])
    ops, goals = r.chain([act("place", "x", "hall"), act("grab", "y"), act("stow", "y")], goal)
    ops, goals, last = r.select_parallel_ops(ops, goals)
    assert last == 0
    return r, goal, gather(r, ops, goals, last)


def test_gather_moves_the_prerequisites_of_a_combinable_step_in_front_of_the_group():
    r, goal, (new, new_goals, last) = _gather_case(max_combined=3)
    assert [str(x) for x in new] == ["grab(y)", "place(x, hall)", "stow(y)"]
    assert last == 0  # grab(y) shares nothing with place(x): taken alone, the group is formed after it
    assert (new, new_goals) == r.valid(new, goal)
    assert any(m.startswith("gathered grab(y)") for m in r.moves)
    # once grab(y) is done, SelectParallelOps combines the two
    s2 = State([*state(robot="hall", x="hall").atoms(), atom("have", "y")])
    r2 = reorderer(s2, ResourceModel(arrange=_share_declared), min_hidden_to_combine=1, max_combined=3)
    assert r2.select_parallel_ops(*r2.chain(new[1:], goal))[2] == 1


def test_gather_does_nothing_at_the_complexity_limit_or_when_switched_off():
    for cfg in ({"max_combined": 1}, {"max_combined": 3, "gather": False}):
        r, _, (new, _, last) = _gather_case(**cfg)
        assert [str(x) for x in new] == ["place(x, hall)", "grab(y)", "stow(y)"] and last == 0
        assert not r.moves


def test_gather_never_moves_prerequisites_that_use_the_group_resources():
    from nowplan.acting.gather import gather

    # fetch(y) gives have(y) like grab(y) but uses the doorway, as the group does: doing it first
    # would take the group's resource away, so the plan is left as it is
    fetch = Operator("fetch", (o,), (Precondition(atom("obj_at", o, "shelf"), 2),),
                     (atom("have", o), atom("obj_at", o, "shelf", value=False)), cost=1.0,
                     resources=(Resource(("doorway",), CT),))
    toy = Domain("toy-rooms-fetch", PREDS, (*OPS, fetch), conflicts=(one_place,))
    s = state(robot="hall", x="hall", y="shelf")
    r = Reorderer(toy, OBJECTS, s, LevelMap(toy.top_level), ResourceModel(arrange=_share_declared),
                  PeepholeConfig(min_hidden_to_combine=1, max_combined=3))
    goal = Goal.of([atom("inside", "x"), atom("inside", "y")])
    ops, goals = r.chain([act("place", "x", "hall"), fetch.instantiate({o: "y"}), act("stow", "y")], goal)
    assert r.arrange(Subgoal((ops[0],), goals[1]), Subgoal((ops[2],), goals[3])) is Arrange.COMBINE
    new, _, last = gather(r, ops, goals, 0)
    assert new == ops and last == 0 and not r.moves


def test_gather_never_moves_prerequisites_held_by_different_resources():
    from nowplan.acting.gather import gather

    # stow(y) needs have(y), which takes two steps on two different holders (a truck leg and a
    # plane leg, say): they cannot be taken as one combined step, so nothing is gathered
    lift = Operator("lift", (o,), (Precondition(atom("obj_at", o, "shelf"), 2),),
                    (atom("carried", o), atom("obj_at", o, "shelf", value=False)), cost=1.0,
                    resources=(Resource(("arm",), SH),))
    hand = Operator("hand", (o,), (Precondition(atom("carried", o), 2),),
                    (atom("have", o), atom("carried", o, value=False)), cost=1.0,
                    resources=(Resource(("cart",), SH),))
    toy = Domain("toy-rooms-two-legs", PREDS, (*OPS, lift, hand), conflicts=(one_place,))
    s = state(robot="hall", x="hall", y="shelf")

    def run(ops_after):
        r = Reorderer(toy, OBJECTS, s, LevelMap(toy.top_level), ResourceModel(arrange=_share_declared),
                      PeepholeConfig(min_hidden_to_combine=1, max_combined=3))
        goal = Goal.of([atom("inside", "x"), atom("inside", "y")])
        ops, goals = r.chain([act("place", "x", "hall"), *ops_after, act("stow", "y")], goal)
        return ops, gather(r, ops, goals, 0)[0]

    ops, new = run([lift.instantiate({o: "y"}), hand.instantiate({o: "y"})])
    assert new == ops
    # with one holder for both legs the prerequisites are gathered
    hand_arm = Operator("hand", (o,), hand.preconditions, hand.effects, cost=1.0,
                        resources=(Resource(("arm",), SH),))
    toy = Domain("toy-rooms-one-leg", PREDS, (*OPS, lift, hand_arm), conflicts=(one_place,))
    ops, new = run([lift.instantiate({o: "y"}), hand_arm.instantiate({o: "y"})])
    assert [x.name for x in new] == ["lift", "hand", "place", "stow"]


@pytest.mark.parametrize("fallout", [500, 0])
def test_a_step_of_a_given_up_combination_refined_alone_gets_the_fallout_budget(fallout: int):
    from types import SimpleNamespace

    from nowplan.planning.plan import PlanResult, PlanStatus
    from nowplan.planning.regression import PlannerConfig

    s, plan, own = _three_carries()
    m = Peephole(PeepholeConfig(max_combined=2, min_hidden_to_combine=1, fallout_nodes=fallout))
    ex = _toy_executive(s)
    frame = SimpleNamespace(plan=plan, plan_id=1, i=0, root=False, info={}, n=len(plan.steps))
    m.next_step(ex, frame)
    assert frame.info["joint"] == 2 and not frame.info["fallout"]  # combined: the joint budget applies
    combined = {a.key for a in frame.plan.actions[:2]}
    base = PlannerConfig()
    # before any combination failed, a step taken alone is planned with the planner's own budgets
    m2 = Peephole(PeepholeConfig(max_combined=1, fallout_nodes=fallout))
    alone = SimpleNamespace(plan=plan, plan_id=2, i=0, root=False, info={}, n=len(plan.steps))
    m2.next_step(ex, alone)
    assert not alone.info["fallout"] and m2.planner_config(ex, alone, Goal(), base) is None
    # the joint subgoal ran out of nodes: its steps, chosen alone from now on, get the fallout budget
    m.after_plan_failure(ex, frame, plan.steps[-1].goal, PlanResult(PlanStatus.NODE_LIMIT, reason="budget"))
    frame.i = 0
    step = m.next_step(ex, frame)
    assert frame.info["joint"] is None and step.action.key in combined
    cfg = m.planner_config(ex, frame, Goal(), base)
    if fallout:
        assert frame.info["fallout"] == frame.i
        assert cfg is not None and cfg.call_nodes == fallout and cfg.max_nodes <= fallout
    else:
        assert not frame.info["fallout"] and cfg is None


# ------------------------------------------------------------------ can_follow (before validity)

_POOL = [act("goto", p, q) for p, q in [("door", "hall"), ("hall", "door"), ("hall", "yard"), ("yard", "hall"),
                                        ("hall", "shelf"), ("shelf", "hall")]]
_POOL += [act("place", x, p) for x in ("x", "y") for p in ("hall", "yard")] + [act("close")]
_POOL += [act("grab", x) for x in ("x", "y")] + [act("stow", x) for x in ("x", "y")]
_POOL += [act("carry", x, p) for x in ("x", "y") for p in ("hall", "yard")]


@pytest.mark.parametrize("levels_top", [None, 1])
@settings(max_examples=200, deadline=None)
@given(st.sampled_from(PLACES), st.sampled_from(PLACES), st.sampled_from(PLACES), st.data())
def test_can_follow_never_refuses_a_move_that_validity_keeps(
    levels_top: int | None, robot: str, x_at: str, y_at: str, data: st.DataObject
) -> None:
    """can_follow(a, before) False => no valid plan keeps a right after before (SelectGap's and
    SelectParallelOps' moves), on random executable tails of the toy domain (their goal: what they
    make true) at two abstraction levels."""
    s = state(robot, x=x_at, y=y_at)
    true = {x.key for x in s.atoms() if x.value is True}
    ops = []
    for _ in range(data.draw(st.integers(2, 7))):
        ok = [a for a in _POOL if all((p.key in true) == bool(p.value) for p in a.preconditions(None))]
        if not ok:
            break
        a = ok[data.draw(st.integers(0, len(ok) - 1))]
        for e in a.effects():
            (true.add if e.value else true.discard)(e.key)
        ops.append(a)
    made = [e for a in ops for e in a.effects() if e.value is True and e.key in true and not TOY.holds(e, s)]
    if len(ops) < 2 or not made:
        return
    goal = Goal.of(made)
    levels = LevelMap(TOY.top_level if levels_top is None else levels_top)
    r = Reorderer(TOY, OBJECTS, s, levels, ResourceModel(), PeepholeConfig())
    for j in range(1, len(ops)):
        for last in range(-1, j - 1):  # -1: ops[j] moved first (SelectGap)
            before = ops[: last + 1]
            new = [*before, ops[j], *ops[last + 1 : j], *ops[j + 1 :]]
            res = r.valid(new, goal)
            if res is not None and res[0][: last + 2] == new[: last + 2]:
                assert r.can_follow(ops[j], before), (new, before)

