"""Refinements made without a planner call (acting/refine.py ``direct_refinement``).

Unit tests on the shipped gripper domain under its automatic hierarchy (``pick``/``drop`` hide
``at-robby``): the one- and two-step refinements of ``drop``, no chain where one action cannot
supply what the step exposes, a learnt nogood respected; a hypothesis property test that on
random states and refined steps a direct refinement is a plan at its levels (each action's kept
preconditions hold when it runs, and its pre-images hold on the way) and is no longer than the
shortest plan a breadth-first search finds; and runs of the executive that use them.
"""

from __future__ import annotations

from collections import deque
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.acting.hpn import Executive
from nowplan.acting.metrics import Outcome
from nowplan.acting.refine import DIRECT_STEPS, direct_refinement
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Atom, Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.domains.registry import Episode
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.problem_hierarchy import prepare_problem
from nowplan.planning.task_grounding import grounding
from nowplan.trace import Trace
from nowplan.worlds.symbolic import SymbolicWorld

GRIPPER = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "gripper"


def gripper() -> Problem:
    return prepare_problem(load_pddl(GRIPPER / "domain.pddl", GRIPPER / "p01.pddl", "auto"))


def executive(prob: Problem, facts: list[Atom]) -> Executive:
    statics = prob.domain.static_predicates
    state = State([*facts, *(a for a in prob.init.atoms() if a.predicate in statics)])
    return Executive(prob, SymbolicWorld(prob.domain, state, seed=0), SymbolicBelief(state),
                     parse_strategy("hpn+refine-flat"))


def act(prob: Problem, name: str, *args: str) -> Action:
    return Action(next(o for o in prob.domain.operators if o.name == name), tuple(args))


def carrying(room: str) -> list[Atom]:
    return [atom("at-robby", room), atom("carry", "ball1", "left"), atom("free", "right"),
            atom("at", "ball2", "rooma")]


def test_the_hierarchy_hides_at_robby_from_drop() -> None:
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    top = LevelMap(prob.domain.top_level)
    assert not top.is_primitive(drop)
    assert top.next_level(drop).is_primitive(drop)


def test_a_drop_where_the_robot_stands_is_one_step() -> None:
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    levels = LevelMap(prob.domain.top_level).next_level(drop)
    plan = direct_refinement(executive(prob, carrying("roomb")), Goal.of([atom("at", "ball1", "roomb")]),
                             levels, drop)
    assert plan is not None
    assert [s.action.pddl() for s in plan.steps if s.action is not None] == ["(drop ball1 roomb left)"]


def test_a_drop_in_the_other_room_moves_the_robot_first() -> None:
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    levels = LevelMap(prob.domain.top_level).next_level(drop)
    goal = Goal.of([atom("at", "ball1", "roomb"), atom("at", "ball2", "rooma")])
    ex = executive(prob, carrying("rooma"))
    plan = direct_refinement(ex, goal, levels, drop)
    assert plan is not None
    assert [s.action.pddl() for s in plan.steps if s.action is not None] == [
        "(move rooma roomb)", "(drop ball1 roomb left)"]
    assert ex.domain.satisfies(ex.belief, plan.preimage(0))
    assert plan.steps[-1].goal == goal


def test_what_the_step_needs_may_come_from_two_actions() -> None:
    # the ball still lies in room a: drop needs carry (pick) and at-robby roomb (move), two achievers;
    # move adds the one and leaves the other to pick before it
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    levels = LevelMap(prob.domain.top_level).next_level(drop)
    facts = [atom("at-robby", "rooma"), atom("free", "left"), atom("free", "right"),
             atom("at", "ball1", "rooma"), atom("at", "ball2", "rooma")]
    ex = executive(prob, facts)
    goal = Goal.of([atom("at", "ball1", "roomb")])
    plan = direct_refinement(ex, goal, levels, drop)
    assert plan is not None
    assert [s.action.pddl() for s in plan.steps if s.action is not None] == [
        "(pick ball1 rooma left)", "(move rooma roomb)", "(drop ball1 roomb left)"]
    assert ex.domain.satisfies(ex.belief, plan.preimage(0))
    assert plan.steps[-1].goal == goal


def test_no_action_before_an_abstract_step_destroys_what_it_needs_later() -> None:
    # the chain [move, pick, drop] is as cheap as [pick, move, drop] and valid at these levels (pick's
    # at-robby is hidden), but the move would undo what the abstract pick needs once refined
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    levels = LevelMap(prob.domain.top_level).next_level(drop)
    facts = [atom("at-robby", "rooma"), atom("free", "left"), atom("free", "right"),
             atom("at", "ball1", "rooma")]
    plan = direct_refinement(executive(prob, facts), Goal.of([atom("at", "ball1", "roomb")]), levels, drop)
    assert plan is not None
    steps = [s.action.pddl() for s in plan.steps if s.action is not None]
    assert steps.index("(pick ball1 rooma left)") < steps.index("(move rooma roomb)")


def test_a_chain_never_starts_with_an_action_that_does_not_apply_now() -> None:
    # nothing adds carry(ball1, left) from here (the ball is nowhere): no chain
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    levels = LevelMap(prob.domain.top_level).next_level(drop)
    facts = [atom("at-robby", "rooma"), atom("free", "left"), atom("free", "right")]
    assert direct_refinement(executive(prob, facts), Goal.of([atom("at", "ball1", "roomb")]), levels, drop) is None


def test_a_learnt_nogood_is_not_used_first() -> None:
    prob = gripper()
    drop = act(prob, "drop", "ball1", "roomb", "left")
    levels = LevelMap(prob.domain.top_level).next_level(drop)
    goal = Goal.of([atom("at", "ball1", "roomb")])
    ex = executive(prob, carrying("rooma"))
    ex.nogoods.learn(goal, levels, act(prob, "move", "rooma", "roomb").key)
    assert direct_refinement(ex, goal, levels, drop) is None
    ex.nogoods.clear()
    assert direct_refinement(ex, goal, levels, drop) is not None


# ---------------------------------------------------------------- property: sound and shortest

def _applicable(a: Action, levels: LevelMap, state: frozenset[Atom]) -> bool:
    return all((p in state) if p.value is True else (p.negate() not in state)
               for p in a.preconditions(levels.level(a)))


def _apply(a: Action, state: frozenset[Atom]) -> frozenset[Atom]:
    out = set(state)
    for e in a.effects():
        if e.value is True:
            out.add(e)
        else:
            out.discard(e.negate())
    return frozenset(out)


def _holds(goal: Goal, state: frozenset[Atom]) -> bool:
    return all((a in state) if a.value is True else (a.negate() not in state) for a in goal.atoms)


def _shortest(actions: list[Action], levels: LevelMap, start: frozenset[Atom], goal: Goal, bound: int) -> int | None:
    """The length of a shortest plan for ``goal`` at ``levels`` (no swap), at most ``bound``, by BFS."""
    seen = {start}
    frontier = deque([(start, 0)])
    while frontier:
        s, n = frontier.popleft()
        if _holds(goal, s):
            return n
        if n == bound:
            continue
        for a in actions:
            if levels.floored([a]) is levels and _applicable(a, levels, s):
                t = _apply(a, s)
                if t not in seen:
                    seen.add(t)
                    frontier.append((t, n + 1))
    return None


ROOMS, BALLS, HANDS = ("rooma", "roomb"), ("ball1", "ball2"), ("left", "right")


@st.composite
def situations(draw: st.DrawFn) -> tuple[list[Atom], int, list[str]]:
    """A consistent gripper state, a refined step (its index among the ground actions), goal extras."""
    facts = [atom("at-robby", draw(st.sampled_from(ROOMS)))]
    held: set[str] = set()
    for b in BALLS:
        where = draw(st.sampled_from(ROOMS + HANDS))
        if where in HANDS and where not in held:
            held.add(where)
            facts.append(atom("carry", b, where))
        else:
            facts.append(atom("at", b, where if where in ROOMS else "rooma"))
    facts += [atom("free", h) for h in HANDS if h not in held]
    return facts, draw(st.integers(0, 10_000)), draw(st.lists(st.sampled_from(BALLS), max_size=2))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(situations())
def test_direct_refinements_are_plans_and_shortest(sit: tuple[list[Atom], int, list[str]]) -> None:
    facts, pick, keep = sit
    prob = gripper()
    ex = executive(prob, facts)
    top = LevelMap(prob.domain.top_level)
    actions = sorted(grounding(prob.domain, prob.objects, ex.belief, top.top).actions, key=lambda a: a.pddl())
    abstract = [a for a in actions if not top.is_primitive(a)]
    refined = abstract[pick % len(abstract)]
    levels = top.next_level(refined)
    state = frozenset(ex.belief.atoms())
    # the step's goal: its own effects and where some balls are now (kept while it is refined)
    extra = [a for a in facts if a.predicate in ("at", "carry") and a.args[0] in keep]
    goal = Goal.of([*(e for e in refined.effects() if e.value is True), *extra])
    plan = direct_refinement(ex, goal, levels, refined)
    if plan is None:
        return
    steps = [s.action for s in plan.steps if s.action is not None]
    assert steps[-1] == refined and 1 <= len(steps) <= DIRECT_STEPS
    s = state
    assert _holds(plan.preimage(0), s)
    for i, a in enumerate(steps, start=1):
        assert _applicable(a, levels, s), f"{a.pddl()} not applicable at its level in {sorted(map(str, s))}"
        s = _apply(a, s)
        assert _holds(plan.steps[i].goal, s)
    assert _holds(goal, s)
    best = _shortest(actions, levels, state, goal, len(steps))
    assert best is not None and best >= len(steps) or _holds(goal, state)


# ---------------------------------------------------------------- the executive

def test_auto_hpn_refines_gripper_mostly_without_planner_calls() -> None:
    prob = gripper()
    strat = parse_strategy("hpn+refine-flat")
    trace = Trace()
    m = run_episode(Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), "p01"),
                    strat, seed=0, trace=trace)
    assert m.outcome is Outcome.REACHED
    methods = [e["method"] for e in trace.events if e["event"] == "plan"]
    assert methods.count("direct") >= len(methods) - 1  # the root plan is the only planner call


def test_nodirect_refines_every_step_with_a_planner_call() -> None:
    prob = gripper()
    trace = Trace()
    m = run_episode(Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), "p01"),
                    parse_strategy("hpn+refine-flat+nodirect"), seed=0, trace=trace)
    assert m.outcome is Outcome.REACHED
    methods = [e["method"] for e in trace.events if e["event"] == "plan"]
    assert len(methods) > 1 and "direct" not in methods



ZENO = Path(__file__).resolve().parents[1] / "benchmarks" / "classical" / "zenotravel"


def test_an_empty_aircraft_elsewhere_is_refuelled_and_flown_first() -> None:
    prob = prepare_problem(load_pddl(ZENO / "domain.pddl", ZENO / "p01.pddl", "auto"))
    board = act(prob, "board", "person1", "plane1", "city0")
    levels = LevelMap(prob.domain.top_level).next_level(board)
    facts = [atom("at", "plane1", "city1"), atom("fuel-level", "plane1", "fl0"),
             atom("at", "person1", "city0"), atom("at", "person2", "city0")]
    ex = executive(prob, facts)
    plan = direct_refinement(ex, Goal.of([atom("in", "person1", "plane1"), atom("at", "person2", "city0")]),
                             levels, board)
    assert plan is not None
    assert [s.action.pddl() for s in plan.steps if s.action is not None] == [
        "(refuel plane1 city1 fl0 fl1)", "(fly plane1 city1 city0 fl1 fl0)", "(board person1 plane1 city0)"]
    assert ex.domain.satisfies(ex.belief, plan.preimage(0))
