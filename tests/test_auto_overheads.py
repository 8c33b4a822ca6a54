"""The executive's bookkeeping under --criticality auto: refine-flat's cycle check, a plan's trace
record, and the grounding cache a benchmark clears (issue 18's whole-run accounting)."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.acting.refine_flat import CYCLE_VISITS, FlatSteps, refinement_key
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Atom, Goal, Var
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.planning.plan import Plan, PlanStep, goal_text
from nowplan.planning.task_grounding import adders_of, cached_grounding, clear_cache, grounding
from nowplan.trace import Trace
from nowplan.worlds.base import Observation


class _Ex:
    """The parts of an executive that FlatSteps.check_cycle reads."""

    def __init__(self, state: State) -> None:
        self.belief = SymbolicBelief(state)
        self.stack: list[Any] = [SimpleNamespace(root=True, i=1, plan_id=0), SimpleNamespace(root=False)]
        self.last_observation = Observation(True)
        self.trace = Trace(None)

    def pop(self, why: str) -> None:
        self.stack.pop()


def test_cycle_check_counts_equal_states_not_state_objects() -> None:
    flat = FlatSteps()
    ex = _Ex(State([Atom("a")]))
    for k in range(CYCLE_VISITS):
        # a fresh but equal State each time, as the belief makes after every action
        ex.belief.state = State([Atom("a")])
        ex.stack[1:] = [SimpleNamespace(root=False)]
        flat.check_cycle(ex)  # type: ignore[arg-type]
        if k < CYCLE_VISITS - 1:
            assert refinement_key(ex.stack[0]) not in flat
            ex.belief.state = State([Atom("b")])  # another state in between
            flat.check_cycle(ex)  # type: ignore[arg-type]
    assert refinement_key(ex.stack[0]) in flat
    assert len(ex.stack) == 1  # the hierarchical plans under the root are dropped


def test_a_failed_action_clears_the_visits() -> None:
    flat = FlatSteps()
    ex = _Ex(State([Atom("a")]))
    for _ in range(CYCLE_VISITS - 1):
        flat.check_cycle(ex)  # type: ignore[arg-type]
    ex.last_observation = Observation(False)
    flat.check_cycle(ex)  # type: ignore[arg-type]
    ex.last_observation = Observation(True)
    flat.check_cycle(ex)  # type: ignore[arg-type]
    assert refinement_key(ex.stack[0]) not in flat


def _domain() -> Domain:
    preds = {n: Predicate(n, 1) for n in ("p", "q")}
    x = Var("x")
    ops = (Operator("go", (x,), (Precondition(Atom("p", (x,)), 1),), (Atom("q", (x,)),)),)
    return Domain("d", preds, ops)


def test_plan_trace_record_writes_every_preimage_atom() -> None:
    dom = _domain()
    g1 = Goal.of([Atom("p", ("a",)), Atom("q", ("b",))], dom.rules)
    g2 = Goal.of([Atom("q", ("a",)), Atom("q", ("b",))], dom.rules)
    act = dom.operators[0].instantiate(dict(zip(dom.operators[0].params, ("a",), strict=True)))
    plan = Plan((PlanStep(None, g1), PlanStep(act, g2)), flat_levels())
    rec = plan.to_json()
    assert [r["preimage"] for r in rec] == [[str(x) for x in g1], [str(x) for x in g2]]


def test_clear_cache_makes_the_next_grounding_anew_with_the_same_actions() -> None:
    dom = _domain()
    objs = {"a": None, "b": None}
    init = State([Atom("p", ("a",))])
    first = grounding(dom, objs, init, -1)
    assert grounding(dom, objs, init, -1) is first  # cached
    clear_cache()
    again = grounding(dom, objs, init, -1)
    assert again is not first
    assert [a.key for a in again.actions] == [a.key for a in first.actions] == [("go", ("a",))]


_FLUENTS = [("p", ("a",)), ("p", ("b",)), ("q", ("a", "b")), ("r", ())]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(_FLUENTS), max_size=4, unique=True),
       st.lists(st.lists(st.tuples(st.sampled_from(_FLUENTS), st.sampled_from([True, False, 1, 2])),
                         max_size=4), max_size=5),
       st.booleans())
def test_state_hash_after_apply_is_the_fresh_states(init: list[tuple[str, tuple[str, ...]]],
                                                    steps: list[list[tuple[Any, Any]]], hashed: bool) -> None:
    """apply updates the hash per effect: the same as a state built from the same fluents."""
    s = State([Atom(p, args) for p, args in init])
    if hashed:
        hash(s)  # the incremental path (a known hash) or, if not, the full one
    for effects in steps:
        s = s.apply([Atom(p, args, v) for (p, args), v in effects])
        fresh = State(list(s.atoms()))
        assert s == fresh and hash(s) == hash(fresh)
        assert State([*s.atoms()]) == s


def test_goal_text_and_a_shared_memo_write_what_str_writes() -> None:
    dom = _domain()
    goals = [Goal.of([Atom("p", (x,)), Atom("q", (y,), False)], dom.rules) for x, y in (("b", "a"), ("a", "b"))]
    made: dict[Any, Any] = {}
    for g in goals * 2:
        assert goal_text(g, made) == [str(a) for a in g]
    plan = Plan((PlanStep(None, goals[0]), PlanStep(dom.operators[0].instantiate({Var("x"): "a"}), goals[1])),
                flat_levels())
    assert plan.to_json(made) == plan.to_json()


def test_cached_grounding_never_grounds_and_adders_index_its_actions() -> None:
    dom = _domain()
    objs = {"a": None, "b": None}
    init = State([Atom("p", ("a",)), Atom("p", ("b",))])
    clear_cache()
    assert cached_grounding(dom, objs, init, -1) is None  # nothing grounded yet: no grounding made
    g = grounding(dom, objs, init, -1)
    assert cached_grounding(dom, objs, init, -1) is g
    # a belief with a fact the grounding never reached is not covered
    assert cached_grounding(dom, objs, State([Atom("p", ("a",)), Atom("r", ("a",))]), -1) is None
    index = adders_of(g)
    assert adders_of(g) is index
    assert {a: [x.key for x in acts] for a, acts in index.items()} == {
        Atom("q", ("a",)): [("go", ("a",))], Atom("q", ("b",)): [("go", ("b",))]}


CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"


@pytest.mark.parametrize(("domain", "problem"), [("gripper", "p03"), ("logistics", "p03"), ("zenotravel", "p03")])
def test_direct_refinements_from_the_grounding_index_match_the_grounders(
        domain: str, problem: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """The achievers read from the run's concrete grounding give the run the lifted grounder gives."""
    import nowplan.planning.task_grounding as tg
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import Episode
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.problem_hierarchy import prepare_problem
    from nowplan.worlds.symbolic import SymbolicWorld

    def run() -> tuple[str, list[str]]:
        clear_cache()
        prob = prepare_problem(load_pddl(CLASSICAL / domain / "domain.pddl", CLASSICAL / domain / f"{problem}.pddl",
                                         "auto"))
        ep = Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), problem)
        with Trace(None) as tr:
            m = run_episode(ep, parse_strategy("hpn+refine-flat"), seed=0, trace=tr)
        return m.outcome.value, [e["action"] for e in tr.events if e["event"] == "action"]

    with_index = run()
    monkeypatch.setattr(tg, "cached_grounding", lambda *a, **k: None)  # the grounder's answers only
    assert run() == with_index
    assert with_index[0] == "reached"


def _reference_irreversible(prob: Any, below_top: Any) -> Any:
    """The dead-end test action by action, every adder's preconditions made up front (the definition
    :func:`nowplan.planning.dead_ends.irreversible_step` groups and evaluates lazily)."""
    from nowplan.planning.dead_ends import _restorable

    g = grounding(prob.domain, prob.objects, prob.init, -1)
    goal = {a for a in prob.goal.atoms if a.value is True}
    deleted = {e.negate() for a in g.actions for e in a.effects() if e.value is False}
    for act in g.actions:
        if not below_top(act):
            continue
        adds = {e for e in act.effects() if e.value is True}
        dels = {e.negate() for e in act.effects() if e.value is False} - adds
        if not dels:
            continue
        back = _restorable(set(dels), lambda d: [frozenset(p for p in a.preconditions() if p.value is True)
                                                 for a in g.actions if d in a.effects()])

        def harmless(lost: Atom) -> bool:
            return lost not in goal and all(
                e.value is not True or (e in adds and e not in deleted)
                for c in g.actions if lost in c.preconditions() for e in c.effects())

        lost = sorted((d for d in dels - back if not harmless(d)), key=str)
        if lost:
            return act.key, lost[0]
    return None


@st.composite
def lifted_problems(draw: st.DrawFn) -> Any:
    from nowplan.core.domain import Problem

    x, y = Var("x"), Var("y")
    preds = {"p": Predicate("p", 1), "q": Predicate("q", 1), "r": Predicate("r", 2)}
    lits = st.sampled_from([Atom("p", (x,)), Atom("p", (y,)), Atom("q", (x,)), Atom("q", (y,)),
                            Atom("r", (x, y)), Atom("r", (y, x)), Atom("p", ("a",))])
    ops = []
    for i in range(draw(st.integers(1, 4))):
        pre = draw(st.lists(lits, max_size=2, unique=True))
        add = draw(st.lists(lits, max_size=1, unique=True))  # few adds: atoms lost for ever are common
        dele = [d for d in draw(st.lists(lits, min_size=1, max_size=2, unique=True)) if d not in add]
        ops.append(Operator(f"o{i}", (x, y), tuple(Precondition(a, 1) for a in pre),
                            (*(Atom(d.predicate, d.args, False) for d in dele), *add)))
    dom = Domain("lifted", preds, tuple(ops))
    objs = ("a", "b", "c")
    facts = st.sampled_from([Atom("p", (o,)) for o in objs] + [Atom("q", (o,)) for o in objs]
                            + [Atom("r", (o, u)) for o in objs for u in objs])
    init = State(draw(st.lists(facts, min_size=2, max_size=8, unique=True)))
    goal = Goal.of(draw(st.lists(facts, min_size=1, max_size=2, unique=True)), dom.rules)
    return Problem(dom, {o: None for o in objs}, init, goal, "lifted")


@settings(max_examples=300, deadline=None)
@given(lifted_problems(), st.sets(st.sampled_from(["o0", "o1", "o2", "o3"])))
def test_grouped_dead_end_test_matches_the_action_by_action_definition(prob: Any, below: set[str]) -> None:
    from nowplan.planning.dead_ends import irreversible_step

    clear_cache()

    def below_top(a: Any) -> bool:
        return a.operator.name in below

    found = irreversible_step(prob, below_top)
    assert (None if found is None else (found.action.key, found.atom)) == _reference_irreversible(prob, below_top)


def test_an_instance_whose_add_cancels_its_delete_does_not_stand_for_its_siblings() -> None:
    """burn(x, y) moves p from x to y along next: burn(a, a) deletes nothing, burn(a, b) loses p(a) for
    ever; grouping the instances by their deletes' arguments alone would let the first hide the second
    (burn(a, b) needs ready(b), which arm(a) gives after burn(a, a): it is grounded second)."""
    from nowplan.core.domain import Problem
    from nowplan.planning.dead_ends import irreversible_step

    x, y = Var("x"), Var("y")
    burn = Operator("burn", (x, y), (Precondition(Atom("p", (x,)), 1), Precondition(Atom("next", (x, y)), 1),
                                     Precondition(Atom("ready", (y,)), 1)),
                    (Atom("p", (x,), False), Atom("p", (y,)), Atom("done", (x,))))
    arm = Operator("arm", (x,), (Precondition(Atom("done", (x,)), 1),), (Atom("ready", ("b",)),))
    dom = Domain("burn", {n: Predicate(n, k) for n, k in (("p", 1), ("next", 2), ("ready", 1), ("done", 1))},
                 (burn, arm))
    init = State([Atom("p", ("a",)), Atom("ready", ("a",)), Atom("next", ("a", "a")), Atom("next", ("a", "b"))])
    prob = Problem(dom, {"a": None, "b": None}, init, Goal.of([Atom("p", ("b",))], dom.rules), "burn")
    clear_cache()

    def below_top(a: Any) -> bool:
        return a.operator.name == "burn"

    assert [a.key for a in grounding(dom, prob.objects, init, -1).actions][0] == ("burn", ("a", "a"))
    found = irreversible_step(prob, below_top)
    assert found is not None and found.action.key == ("burn", ("a", "b")) and found.atom == Atom("p", ("a",))
    assert (found.action.key, found.atom) == _reference_irreversible(prob, below_top)
