"""A hierarchical call whose shortcuts fail falls back on the forward search before the full regression.

Found by the held-out warehouse domain (examples/warehouse, issue 14): digging boxes out of stacks at
an abstract level (the hand hidden a class below) made the regression search hopeless — subgoals
that grow with every box moved aside, a branching of every place a box may go: 2,000 nodes in ~9 CPU
s without a plan, while the forward search at the same level needs a handful of expansions.  The
regression's shortcuts also ran into the call's whole time limit; they now get a quarter of it
when the forward search may follow (``regression.SHORTCUT_SHARE``).
"""

from __future__ import annotations

import random
import time

from nowplan.api import (
    Domain, Goal, Operator, PlannerConfig, Precondition, Predicate, State, SymbolicBelief, Var, at_most_one, atom,
    exactly_one, excludes, plan,
)
from nowplan.core.levels import LevelMap
from nowplan.planning import regression

b, u, s = Var("b"), Var("u"), Var("s")
TOP, HAND = 2, 1


def _pre(name: str, *args: object, crit: int = TOP) -> Precondition:
    return Precondition(atom(name, *args), crit)


def _domain() -> Domain:
    preds = {p.name: p for p in (
        Predicate("on", 2, ("box", "support")), Predicate("in_slot", 2, ("box", "slot")),
        Predicate("clear", 1, ("support",)), Predicate("holding", 1, ("box",)), Predicate("hand_empty", 0))}
    take = (atom("holding", b), atom("in_slot", b, s, value=False), atom("hand_empty", value=False))
    drop = (atom("in_slot", b, s), atom("holding", b, value=False), atom("hand_empty"))
    ops = (
        Operator("pick", (b, s), (_pre("on", b, s), _pre("clear", b), _pre("in_slot", b, s), _pre("hand_empty", crit=HAND)),
                 take + (atom("on", b, s, value=False), atom("clear", s)), param_types=("box", "slot")),
        Operator("unstack", (b, u, s), (_pre("on", b, u), _pre("clear", b), _pre("in_slot", b, s),
                                        _pre("hand_empty", crit=HAND)),
                 take + (atom("on", b, u, value=False), atom("clear", u)), param_types=("box", "box", "slot")),
        Operator("put", (b, s), (_pre("holding", b), _pre("clear", s)),
                 drop + (atom("on", b, s), atom("clear", s, value=False)), param_types=("box", "slot")),
        Operator("stack", (b, u, s), (_pre("holding", b), _pre("clear", u), _pre("in_slot", u, s)),
                 drop + (atom("on", b, u), atom("clear", u, value=False)), param_types=("box", "box", "slot")),
    )
    rules = (exactly_one("on", "holding", key=0), exactly_one("in_slot", "holding", key=0), at_most_one("on", key=1),
             at_most_one("holding", key=()), excludes(atom("clear", u), atom("on", b, u)),
             excludes(atom("hand_empty"), atom("holding", b)))
    return Domain("stacks", preds, ops, types={"support": None, "box": "support", "slot": "support"}, conflicts=rules)


def _problem(dom: Domain) -> tuple[dict[str, str | None], SymbolicBelief, Goal]:
    cols = {"pack": [], "s1": ["b3"], "s2": [], "s3": [], "s4": ["b4", "b8"], "s5": ["b1", "b2", "b6"], "s6": [],
            "s7": ["b5", "b7"], "s8": [], "s9": []}
    facts = [atom("hand_empty")]
    for slot, col in cols.items():
        below = slot
        for x in col:
            facts += [atom("on", x, below), atom("in_slot", x, slot)]
            below = x
        facts.append(atom("clear", below))
    objects: dict[str, str | None] = {**{k: "slot" for k in cols}, **{f"b{i}": "box" for i in range(1, 9)}}
    goal = Goal.of([atom("in_slot", "b5", "pack"), atom("in_slot", "b1", "pack")], dom.rules)
    return objects, SymbolicBelief(State(facts)), goal


def test_abstract_call_falls_back_on_the_forward_search() -> None:
    dom = _domain()
    objects, belief, goal = _problem(dom)
    t0 = time.process_time()
    res = plan(dom, objects, belief, goal, LevelMap(dom.top_level), PlannerConfig(time_limit=4.0, clock="cpu"),
               rng=random.Random(0))
    assert res.solved, (res.status, res.reason, res.attempts)
    assert any(a.startswith("forward") for a in res.attempts), res.attempts
    assert time.process_time() - t0 < 4.0
    # the plan is valid at its level: every step's pre-image holds where the previous step leaves it
    state = belief.state
    assert res.plan is not None
    for step in res.plan.steps[1:]:
        assert step.action is not None
        state = state.apply(step.action.effects())
    assert all(state.holds(a) for a in goal.atoms)


def test_shortcuts_get_a_share_of_the_time_when_the_forward_search_may_follow() -> None:
    assert 0 < regression.SHORTCUT_SHARE < 0.5
    dom = _domain()
    objects, belief, goal = _problem(dom)
    assert regression.forward_fallback_applies(dom, LevelMap(dom.top_level), PlannerConfig(), None)
    assert not regression.forward_fallback_applies(dom, LevelMap(0), PlannerConfig(), None)  # concrete: forward first
    assert not regression.forward_fallback_applies(dom, LevelMap(dom.top_level), PlannerConfig(engine="regression"),
                                                   None)
