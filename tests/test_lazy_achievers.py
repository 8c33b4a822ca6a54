"""The achievers that direct refinements look up one atom at a time (acting/refine.py ``Achievers``).

They replace an index of the whole grounded task, built once per level and kept for the run:
the lazy answers must agree with that index on every atom asked (the index holds the reachable
actions; an answer may add only actions that no state reached can apply), and must follow the
executive's objects and static facts when they change (the kept index went stale there).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from nowplan.acting.hpn import Executive
from nowplan.acting.refine import direct_refinement
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Atom, Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.problem_hierarchy import prepare_problem
from nowplan.planning.task_grounding import grounding
from nowplan.worlds.symbolic import SymbolicWorld

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"
ZENO = Path(__file__).resolve().parents[1] / "benchmarks" / "classical" / "zenotravel"


def executive(prob: Problem, state: State | None = None) -> Executive:
    s = prob.init if state is None else state
    return Executive(prob, SymbolicWorld(prob.domain, s, seed=0), SymbolicBelief(s), parse_strategy("hpn"))


def full_index(prob: Problem, ex: Executive) -> tuple[dict[Atom, list[Action]], set[Action]]:
    """The index the lazy lookup replaced: every reachable action of the task, by effect."""
    gr = grounding(prob.domain, prob.objects, ex.belief, -1)
    index: dict[Atom, list[Action]] = {}
    for a in gr.actions:
        for e in a.effects():
            index.setdefault(e, []).append(a)
    return index, set(gr.actions)


def problems() -> list[Problem]:
    return [
        load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p02.pddl", DATA / "logistics" / "logistics.crit"),
        prepare_problem(load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl", "auto")),
        prepare_problem(load_pddl(ZENO / "domain.pddl", ZENO / "p01.pddl", "auto")),
    ]


def test_lazy_achievers_equal_the_full_index_on_every_atom_asked() -> None:
    for prob in problems():
        ex = executive(prob)
        index, reachable = full_index(prob, ex)
        lazy = ex.achievers.lookup(ex)
        # every effect of a reachable action, positive and negative, and a few no action has
        asked = sorted(index, key=repr)
        assert asked, prob.name
        for u in asked:
            got = lazy.of(u)
            assert len(set(got)) == len(got)
            # the same reachable actions; anything more no state reached can apply
            assert [a for a in got if a in reachable] != [] and set(got) & reachable == set(index[u]), (prob.name, u)
            assert all(u in a.effects() for a in got)


def test_lazy_achievers_answer_atoms_no_action_achieves_with_nothing() -> None:
    prob = problems()[0]
    ex = executive(prob)
    lazy = ex.achievers.lookup(ex)
    assert lazy.of(atom("in-city", "city1-loc1", "city2")) == []  # a static predicate
    assert lazy.of(atom("serves", "truck1-1", "city2-loc1")) == []


def test_one_of_picks_an_atom_of_need_with_its_achievers() -> None:
    prob = problems()[0]
    ex = executive(prob)
    lazy = ex.achievers.lookup(ex)
    need = [atom("at", "truck1-1", "city1-loc1"), atom("at", "pkg1", "city1-loc1")]
    u, acts = lazy.one_of(need)
    assert u in need and acts == lazy.of(u)
    # once both are known, the one with fewer achievers
    lazy.of(need[1])
    u, acts = lazy.one_of(need)
    assert len(acts) == min(len(lazy.of(x)) for x in need)


def _with_new_place(prob: Problem, ex: Executive) -> tuple[Problem, State]:
    """``prob`` with a new location in city1 that truck1-1 serves (object and static facts)."""
    objects = {**dict(prob.objects), "city1-loc9": "location"}
    facts = [*ex.belief.atoms(), atom("in-city", "city1-loc9", "city1"), atom("serves", "truck1-1", "city1-loc9")]
    return replace(prob, objects=objects), State(facts)


def test_no_stale_achievers_after_an_object_and_its_static_facts_appear() -> None:
    prob = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p01.pddl", DATA / "logistics" / "logistics.crit")
    ex = executive(prob)
    goal_at = atom("at", "truck1-1", "city1-loc9")
    unload = Action(next(o for o in prob.domain.operators if o.name == "unload-truck"), ("pkg1", "truck1-1", "city1-loc9"))
    drive = "(drive-truck truck1-1 city1-airport city1-loc9 city1)"
    before = [a.pddl() for a in ex.achievers.lookup(ex).of(goal_at)]
    assert drive not in before  # no such place yet: in-city fails
    # a direct refinement made before the change (the kept index was built here, and went stale)
    there = Action(unload.operator, ("pkg1", "truck1-1", "city1-loc1"))
    carried = State([a for a in [*ex.belief.atoms(), atom("in", "pkg1", "truck1-1")]
                     if a != atom("at", "pkg1", "city1-airport")])
    ex.belief = SymbolicBelief(carried)
    assert direct_refinement(ex, Goal.of([atom("at", "pkg1", "city1-loc1")]),
                             LevelMap(prob.domain.top_level).next_level(there), there) is not None
    # the executive's view changes (an exogenous change: a new place and the facts that tie it in)
    prob2, state = _with_new_place(prob, ex)
    ex.problem = prob2
    ex.belief = SymbolicBelief(state)
    after = [a.pddl() for a in ex.achievers.lookup(ex).of(goal_at)]
    assert drive in after
    # and the direct refinement of an unload there drives the truck first (the kept index had no drive)
    state2 = State([*state.atoms(), atom("in", "pkg1", "truck1-1")])
    state2 = State([a for a in state2.atoms() if a != atom("at", "pkg1", "city1-airport")])
    ex.belief = SymbolicBelief(state2)
    levels = LevelMap(prob.domain.top_level).next_level(unload)
    plan = direct_refinement(ex, Goal.of([atom("at", "pkg1", "city1-loc9")]), levels, unload)
    assert plan is not None
    assert [s.action.pddl() for s in plan.steps if s.action is not None] == [drive, unload.pddl()]


def test_no_stale_achievers_after_a_static_fact_disappears() -> None:
    prob = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p01.pddl", DATA / "logistics" / "logistics.crit")
    ex = executive(prob)
    target = atom("at", "pkg2", "city2-loc1")
    unload = "(unload-truck pkg2 truck1-2 city2-loc1)"
    assert unload in [a.pddl() for a in ex.achievers.lookup(ex).of(target)]
    # truck1-2 no longer serves city2-loc1 (a road closed): it cannot unload there
    ex.belief = SymbolicBelief(State([a for a in ex.belief.atoms() if a != atom("serves", "truck1-2", "city2-loc1")]))
    assert unload not in [a.pddl() for a in ex.achievers.lookup(ex).of(target)]


class _Pose:
    """A generator's value that cannot be hashed (e.g. an array-valued pose)."""

    __hash__ = None  # type: ignore[assignment]

    def __init__(self, x: float) -> None:
        self.x = x

    def __eq__(self, other: object) -> bool:
        return isinstance(other, _Pose) and other.x == self.x


def test_the_static_join_takes_a_value_that_cannot_be_hashed() -> None:
    # the grounder looks static facts up by their bound arguments; a generator's unhashable value
    # among them falls back to scanning the facts (no TypeError), hashable ones use the index
    from nowplan.core.atoms import Var
    from nowplan.core.domain import Domain, Predicate
    from nowplan.core.operators import Generator, Operator, Precondition
    from nowplan.planning.grounding import Grounder

    to, via, mid = Var("to"), Var("via"), Var("mid")
    preds = {"at": Predicate("at", 1), "road": Predicate("road", 2)}

    def run(value: object) -> list[str]:
        def pick(b: object, goal: object, belief: object, ctx: object) -> object:
            yield {via: value}

        op = Operator("go", (to, via, mid), (Precondition(atom("road", via, mid)),), (atom("at", to),),
                      generators=(Generator("via", (via,), pick),))
        dom = Domain("roads", preds, (op,))
        state = State([atom("road", "x", "y"), atom("road", "x", "z"), atom("road", "w", "y")])
        return [str(a) for a in Grounder(dom, {"x": None, "y": None, "z": None, "w": None, "b": None},
                                         state).achievers(atom("at", "b"), Goal.of([atom("at", "b")]))]

    assert run("x") == ["go(b, x, y)", "go(b, x, z)"]
    assert run(_Pose(1.0)) == []


def test_static_facts_are_read_again_only_after_news() -> None:
    """Between two pieces of news the grounder's signature (objects and static facts) is reused, not read
    from the belief again; an exogenous change (the executive counts it) makes the next lookup read it."""
    prob = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p01.pddl", DATA / "logistics" / "logistics.crit")
    ex = executive(prob)
    target = atom("at", "pkg2", "city2-loc1")
    unload = "(unload-truck pkg2 truck1-2 city2-loc1)"
    first = ex.achievers.lookup(ex)
    assert unload in [a.pddl() for a in first.of(target)]
    assert ex.achievers.lookup(ex).grounder.signature is first.grounder.signature  # no news: reused
    # the world closes a road and the belief adopts its state (same belief object): news
    ex.belief.state = State([a for a in ex.belief.atoms() if a != atom("serves", "truck1-2", "city2-loc1")])
    ex.metrics.exogenous_changes += 1
    again = ex.achievers.lookup(ex)
    assert again.grounder.signature != first.grounder.signature
    assert unload not in [a.pddl() for a in again.of(target)]
