"""TruthMemo: the peephole's truth tests in one belief, memoised per point state, answer as Domain.holds."""

from __future__ import annotations

from typing import Any

from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.acting.reorder import PeepholeConfig, Reorderer, highest_applicable
from nowplan.acting.resources import ResourceModel
from nowplan.acting.truth import TruthMemo
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import atom
from nowplan.core.state import State
from tests.test_peephole import OBJECTS, PLACES, TOY, reorderer, state, toy_errand_plan

ASKED = [atom("robot_at", p) for p in PLACES] + [atom("obj_at", x, p) for x in "xy" for p in PLACES] + [
    atom("inside", "x"), atom("carried", "y"), atom("closed"), atom("closed", value=False)]


def _belief(data: st.DataObject, wrap: bool) -> Any:
    facts = list(state(robot=data.draw(st.sampled_from(PLACES)), x=data.draw(st.sampled_from(PLACES)),
                       y=data.draw(st.sampled_from(PLACES))).atoms())
    facts += [atom(n, *args) for n, args in data.draw(st.lists(st.sampled_from(
        [("inside", ("x",)), ("carried", ("y",)), ("closed", ())]), unique=True))]
    s = State(facts)
    return SymbolicBelief(s) if wrap else s


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_a_memo_answers_as_domain_holds_across_changing_beliefs(data: st.DataObject) -> None:
    """One memo over a sequence of beliefs (a SymbolicBelief whose state is replaced, as after an
    action, and plain states), each asked in a random order and again: every answer is holds'."""
    memo = TruthMemo(TOY)
    wrapped = SymbolicBelief(state())
    for _ in range(data.draw(st.integers(1, 6))):
        b = _belief(data, data.draw(st.booleans()))
        if isinstance(b, SymbolicBelief):
            wrapped.state = b.state  # the executive's belief object stays, its state changes
            b = wrapped
        holds = memo.holds_in(b)
        for a in data.draw(st.lists(st.sampled_from(ASKED), min_size=1, max_size=30)):
            assert holds(a) == TOY.holds(a, b)


def test_a_belief_that_is_no_point_state_is_asked_each_time() -> None:
    """A belief of another kind may answer from more than a state: nothing is remembered for it."""

    class Counting:
        def __init__(self) -> None:
            self.asked = 0

        def value(self, key: Any) -> Any:
            self.asked += 1
            return True if key == ("robot_at", ("hall",)) else None

    b = Counting()
    holds = TruthMemo(TOY).holds_in(b)
    assert holds(atom("robot_at", "hall")) and holds(atom("robot_at", "hall"))
    assert b.asked == 2


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_highest_applicable_with_a_memo_answers_as_without(data: st.DataObject) -> None:
    ops, p = toy_errand_plan()
    memo, watch = TruthMemo(TOY), {}  # type: ignore[var-annotated]
    for _ in range(data.draw(st.integers(1, 8))):
        b = _belief(data, True)
        assert highest_applicable(TOY, b, p, watch, memo.holds_in(b)) == highest_applicable(TOY, b, p)
        with_memo = Reorderer(TOY, OBJECTS, b, p.levels, ResourceModel(), PeepholeConfig(), holds=memo.holds_in(b))
        plain = reorderer(b.state)
        for i, x in enumerate(ops):
            assert with_memo.can_follow(x, ops[:i]) == plain.can_follow(x, ops[:i])
        order = data.draw(st.permutations(ops))
        assert with_memo.valid(order, p.goal) == plain.valid(order, p.goal)
