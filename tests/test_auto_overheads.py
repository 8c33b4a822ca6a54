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
    from nowplan.planning.abstraction import prepare_problem
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
