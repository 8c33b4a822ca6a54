"""The online policy (seed 004 Alg. 1), reuse-enforced replanning (Alg. 2) and deferred streams."""

from __future__ import annotations

import random
from dataclasses import dataclass
from typing import Any, ClassVar

import pytest

from nowplan.acting.deferred import resolve, schedule
from nowplan.acting.online import OnlinePolicy
from nowplan.acting.reuse import FreeVar, constrained_plan, skeleton
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Goal, Var, atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Action, Generator, Operator, Precondition
from nowplan.core.state import State
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.streams import Optimistic, Stream, StreamSet
from nowplan.worlds.base import Observation


@dataclass(frozen=True)
class Conf:
    loc: str
    jitter: float
    constant: ClassVar[bool] = False


O, L, Q, T = Var("o"), Var("l"), Var("q"), Var("t")


def build(streams: StreamSet, rng: random.Random, reuse_here: bool = True) -> Domain:
    def traj(b: Any, g: Any, bel: Any, ctx: Any) -> Any:
        yield {T: streams.optimistic("motion", b[Q])}

    def conf(b: Any, g: Any, bel: Any, ctx: Any) -> Any:
        pairs = [(o, l) for (o, l) in bel.facts("At") if b.get(O, o) == o and b.get(L, l) == l]
        if L in b and O in b:
            pairs = [(b[O], b[L])]
        here = bel.value(("RobotAt", ()))
        for o, loc in pairs:
            if reuse_here and here.loc == loc:
                yield {O: o, L: loc, Q: here}  # where the robot already is, if that works
            yield {O: o, L: loc, Q: Conf(loc, round(rng.uniform(-0.01, 0.01), 6))}

    preds = {
        "RobotAt": Predicate("RobotAt", 0, boolean=False),
        "At": Predicate("At", 2),
        "Holding": Predicate("Holding", 1),
        "HandEmpty": Predicate("HandEmpty", 0),
    }
    move = Operator("move", (Q, T), (), (atom("RobotAt", value=Q),), 1.0,
                    generators=(Generator("motion", (T,), traj),))
    pick = Operator(
        "pick", (O, L, Q),
        (Precondition(atom("At", O, L)), Precondition(atom("RobotAt", value=Q)), Precondition(atom("HandEmpty"))),
        (atom("Holding", O), atom("At", O, L, value=False), atom("HandEmpty", value=False)), 1.0,
        param_types=("obj", "loc", None), generators=(Generator("conf", (O, L, Q), conf),),
    )
    place = Operator(
        "place", (O, L, Q),
        (Precondition(atom("Holding", O)), Precondition(atom("RobotAt", value=Q))),
        (atom("At", O, L), atom("Holding", O, value=False), atom("HandEmpty")), 1.0,
        param_types=("obj", "loc", None), generators=(Generator("conf", (Q,), conf),),
    )
    return Domain("toy", preds, (move, pick, place), types={"obj": None, "loc": None})


class ToyBelief(SymbolicBelief):
    def __init__(self, state: State, streams: StreamSet) -> None:
        super().__init__(state)
        self.streams = streams


class ToyWorld:
    def __init__(self, state: State) -> None:
        self.state = state

    def execute(self, action: Action) -> Observation:
        self.state = self.state.apply(action.effects())
        return Observation(True, self.state)


def motion(belief: Any, earlier: tuple[Action, ...], q: Conf) -> Any:
    start = next((a.args[0] for a in reversed(earlier) if a.name == "move"),
                 belief.value(("RobotAt", ())))
    return ("traj", start, q)


def setup(goal_loc: str = "l2", reuse_here: bool = True) -> tuple[Problem, ToyWorld, ToyBelief, StreamSet]:
    streams = StreamSet([
        Stream("motion", ("q1", "q2"), ("t",), ("Motion",), motion, cost=1.0, expensive=True, likely=True),
        Stream("conf", ("l",), ("q",), ("Kin",), lambda *a: None),
    ])
    dom = build(streams, random.Random(0), reuse_here)
    init = State([atom("RobotAt", value=Conf("l0", 0.0)), atom("At", "a", "l1"), atom("At", "b", "l0"),
                  atom("HandEmpty")])
    goal = Goal.of([atom("At", "a" if goal_loc != "nowhere" else "c", "l2"), atom("At", "b", "l3")])
    objects = {"a": "obj", "b": "obj", "l0": "loc", "l1": "loc", "l2": "loc", "l3": "loc"}
    prob = Problem(dom, objects, init, goal)
    return prob, ToyWorld(init), ToyBelief(init, streams), streams


def test_deferred_streams_are_not_called_before_the_first_action() -> None:
    prob, _, belief, streams = setup()
    res = plan(prob.domain, prob.objects, belief, prob.goal, config=PlannerConfig(seed=0))
    assert res.solved and res.plan is not None
    acts = res.plan.actions
    moves = [a for a in acts if a.name == "move"]
    assert len(moves) >= 3 and all(isinstance(m.args[1], Optimistic) for m in moves)
    assert streams.calls["motion"] == 0  # optimistic during search
    rs = resolve(acts, streams, belief, deferred=True)
    assert rs.ok and streams.calls["motion"] == (1 if acts[0].name == "move" else 0)
    assert rs.deferred == len(moves) - streams.calls["motion"]
    streams.calls.clear()
    rs = resolve(acts, streams, belief, deferred=False)
    assert rs.ok and streams.calls["motion"] == len(moves) and rs.deferred == 0
    # a bound trajectory starts where the previous move ended
    bound = [a for a in rs.actions if a.name == "move"]
    assert bound[1].args[1][1] == bound[0].args[0]
    assert len(schedule(acts, streams, deferred=True)) <= 1


def test_policy_with_deferral_calls_motion_once_per_executed_move() -> None:
    prob, world, belief, streams = setup()
    m = OnlinePolicy(prob, world, belief, parse_strategy("online+deferred")).run()
    assert m.outcome.value == "reached"
    assert streams.calls["motion"] == m.action_counts["move"]
    prob, world, belief, streams = setup()
    m2 = OnlinePolicy(prob, world, belief, parse_strategy("online")).run()
    assert m2.outcome.value == "reached" and streams.calls["motion"] > m2.action_counts["move"]


def test_skeleton_keeps_constants_and_frees_the_rest() -> None:
    prob, _, belief, _ = setup()
    res = plan(prob.domain, prob.objects, belief, prob.goal)
    assert res.plan is not None
    sk = skeleton(res.plan.actions)
    for step, act in zip(sk, res.plan.actions, strict=True):
        assert step.name == act.name
        for s, a in zip(step.args, act.args, strict=True):
            assert (s == a) if isinstance(a, str) else isinstance(s, FreeVar)


def test_constrained_replanning_keeps_the_skeleton() -> None:
    prob, world, belief, _ = setup()
    first = plan(prob.domain, prob.objects, belief, prob.goal)
    assert first.plan is not None
    acts = first.plan.actions
    world.execute(acts[0])
    belief.update(acts[0], Observation(True))
    tail = skeleton(acts[1:])
    res = constrained_plan(prob.domain, prob.objects, belief, prob.goal, tail, time_budget=5.0)
    assert res.solved and res.plan is not None
    assert skeleton(res.plan.actions) == tail
    # fresh values for free variables (configurations are re-sampled)
    assert any(a != b for a, b in zip(res.plan.actions, acts[1:], strict=True))


def test_policy_reuse_follows_the_previous_tail() -> None:
    prob, world, belief, _ = setup()
    pol = OnlinePolicy(prob, world, belief, parse_strategy("online+reuse+deferred"))
    m = pol.run()
    assert m.outcome.value == "reached"
    assert pol.constrained_tried == m.actions - 1 and pol.constrained_ok == pol.constrained_tried
    plans = [[s["action"].split()[0] for s in e["steps"]] for e in pol.trace.of("plan")]
    for a, b in zip(plans, plans[1:]):
        assert b == a[1:]


def test_unreachable_goal_ends_with_a_reason() -> None:
    prob, world, belief, _ = setup(goal_loc="nowhere")
    m = OnlinePolicy(prob, world, belief, parse_strategy("online+reuse+deferred")).run()
    assert m.outcome.value == "failed" and "no plan" in m.reason and m.actions == 0


def test_cost_bound_refuses_expensive_plans() -> None:
    prob, world, belief, _ = setup()
    m = OnlinePolicy(prob, world, belief, parse_strategy("online"), c_star=2.0).run()
    assert m.outcome.value == "failed" and "c*" in m.reason


def test_stream_declarations() -> None:
    s = Stream("m", (), (), (), lambda *a: 1, expensive=True, likely=True)
    assert s.deferrable
    assert not Stream("m", (), (), (), lambda *a: 1, expensive=True, likely=False).deferrable
    assert not Stream("m", (), (), (), lambda *a: 1, expensive=True, never_defer=True).deferrable
    ss = StreamSet([Stream("x", (), (), (), lambda b, e, v: None)])
    assert ss.evaluate("x", None, (), 3) is None and ss.has_failed("x", 3)
    with pytest.raises(Exception, match="unknown stream"):
        ss.optimistic("y")


def test_stream_levels_grow_to_a_maximum_and_reset() -> None:
    ss = StreamSet([])
    assert ss.level == 1
    grown = [ss.grow() for _ in range(ss.max_level + 1)]
    assert grown.count(True) == ss.max_level - 1 and ss.level == ss.max_level
    ss.reset_level()
    assert ss.level == 1


def test_regression_uses_a_heuristic_given_through_the_context() -> None:
    from nowplan.core.levels import flat_levels
    from nowplan.planning.context import PlanningContext
    from nowplan.planning.regression import plan

    prob, _, belief, _ = setup()
    calls: list[int] = []

    def h(goal: Any, b: Any, holds: Any) -> float:
        calls.append(1)
        return float(sum(1 for a in goal.atoms if not holds(a)))

    res = plan(prob.domain, prob.objects, belief, prob.goal, flat_levels(), None, PlanningContext((), {"heuristic": h}))
    assert res.solved and calls
