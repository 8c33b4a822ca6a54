"""``Domain.satisfies`` over a :class:`State` in a domain of plain truth: one dictionary lookup per atom (``State.all_hold``).

A property test: on random states and goals (true, false and other-valued atoms, values stored as
``True``/``1``/``False``/absent), the lookup answers exactly as ``Domain.holds``; domains with
a tested predicate or another value rule keep ``holds``; the executive hands the symbolic
belief's state to it only where the domain's truth is plain.
"""

from __future__ import annotations

from pathlib import Path

from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.acting.hpn import Executive
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import AtLeastRule, Atom, Goal
from nowplan.core.domain import Domain, Predicate
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.worlds.symbolic import SymbolicWorld

PREDS = {"p": Predicate("p", 1), "q": Predicate("q", 2)}
OBJS = ["a", "b", "c"]

keys = st.one_of(st.tuples(st.just("p"), st.tuples(st.sampled_from(OBJS))),
                 st.tuples(st.just("q"), st.tuples(st.sampled_from(OBJS), st.sampled_from(OBJS))))
values = st.sampled_from([True, False, 1, 0, "red", None])


@settings(max_examples=300, deadline=None)
@given(st.dictionaries(keys, values, max_size=8), st.dictionaries(keys, st.sampled_from([True, False, "red", 1]), max_size=6))
def test_the_lookup_answers_as_holds(state_map: dict, goal_map: dict) -> None:  # type: ignore[type-arg]
    domain = Domain("d", PREDS)
    assert domain.plain_truth
    state = State(state_map)
    goal = Goal(frozenset(Atom(k[0], k[1], v) for k, v in goal_map.items()))
    slow = all(domain.holds(a, state) for a in goal.atoms)
    assert domain.satisfies(state, goal) == slow
    assert domain.satisfies(state, list(goal.atoms)) == slow  # (an iterable: atom by atom)
    # the progress guard's count of goal atoms held, by the same lookup
    assert domain.count_holding(state, goal.atoms) == sum(domain.holds(a, state) for a in goal.atoms)


def test_a_tested_predicate_or_another_rule_is_not_plain() -> None:
    tested = {**PREDS, "r": Predicate("r", 0, test=lambda belief, args, value: True)}
    assert not Domain("d", tested).plain_truth
    ruled = {**PREDS, "n": Predicate("n", 1, rule=AtLeastRule())}
    assert not Domain("d", ruled).plain_truth
    # a tested predicate asked true is answered by its test, not by the state
    d = Domain("d", tested)
    assert d.satisfies(State({}), Goal(frozenset([Atom("r", ())])))


def test_the_executive_reads_the_state_of_a_plain_domain() -> None:
    g = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "gripper"
    prob = load_pddl(g / "domain.pddl", g / "p01.pddl")
    ex = Executive(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init),
                   parse_strategy("hpn"))
    assert ex.truth is ex.belief.state
    assert ex.domain.satisfies(ex.truth, prob.goal) == ex.domain.satisfies(ex.belief, prob.goal)


def test_the_online_policy_counts_the_goal_on_the_same_state() -> None:
    from nowplan.belief.symbolic import truth_of

    g = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "gripper"
    prob = load_pddl(g / "domain.pddl", g / "p01.pddl")
    b = SymbolicBelief(prob.init)
    assert truth_of(prob.domain, b) is b.state
    assert prob.domain.count_holding(truth_of(prob.domain, b), prob.goal.atoms) == sum(
        prob.domain.holds(a, b) for a in prob.goal.atoms)
