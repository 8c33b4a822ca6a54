from __future__ import annotations

import pytest

from nowplan.core.atoms import Atom, Goal, Rules, ToleranceRule, Var, atom, conjoin, entails
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.errors import ContradictoryGoalError, ModelError

TOL = Rules({"BVRelPose": ToleranceRule()})


def test_atoms_are_hashable_values():
    a, b = atom("at", "p", "l"), Atom("at", ("p", "l"), True)
    assert a == b and hash(a) == hash(b)
    assert a.negate() == atom("at", "p", "l", value=False)
    assert str(a.negate()) == "not at(p, l)"


def test_tolerance_entailment_tighter_entails_looser():
    tight = Goal.of([atom("BVRelPose", "A", value=0.01)], TOL)
    loose = Goal.of([atom("BVRelPose", "A", value=0.05)], TOL)
    assert entails(tight, loose, TOL)
    assert not entails(loose, tight, TOL)
    merged = conjoin(tight, [atom("BVRelPose", "A", value=0.05)], TOL)
    assert merged is not None and merged == tight


def test_equality_values_contradict():
    with pytest.raises(ContradictoryGoalError, match="cannot both hold"):
        Goal.of([atom("at", "p", "l1"), atom("at", "p", "l1", value=False)])
    g = Goal.of([atom("robot", value="kitchen")])
    assert conjoin(g, [atom("robot", value="hall")]) is None


def test_domain_conflict_rules():
    def one_place(x: Atom, y: Atom) -> bool:
        return x.predicate == y.predicate == "at" and x.args[0] == y.args[0] and x.key != y.key

    rules = Rules(conflicts=(one_place,))
    assert conjoin(Goal(), [atom("at", "p", "a"), atom("at", "p", "b")], rules) is None
    assert conjoin(Goal(), [atom("at", "p", "a"), atom("at", "q", "b")], rules) is not None


def test_entailment_needs_every_atom():
    g1 = Goal.of([atom("a"), atom("b")])
    assert entails(g1, Goal.of([atom("a")]))
    assert not entails(Goal.of([atom("a")]), g1)


def test_state_closed_world_and_apply():
    s = State([atom("on", "a", "b")])
    assert s.holds(atom("on", "a", "b")) and s.holds(atom("on", "b", "a", value=False))
    s2 = s.apply([atom("on", "a", "b", value=False), atom("clear", "b")])
    assert s2.facts("clear") == [("b",)] and not s2.facts("on")
    assert s == State([atom("on", "a", "b")]) and hash(s) == hash(State([atom("on", "a", "b")]))


def test_predicate_test_function_decides_truth():
    # the belief is a plain dict of variances; the fluent is true when variance <= tolerance
    pred = Predicate("BVRelPose", 1, rule=ToleranceRule(), test=lambda b, args, eps: b[args[0]] <= eps)
    dom = Domain("d", {"BVRelPose": pred})
    assert dom.holds(atom("BVRelPose", "A", value=0.05), {"A": 0.02})
    assert not dom.holds(atom("BVRelPose", "A", value=0.01), {"A": 0.02})


def test_unknown_predicate_and_arity_are_model_errors():
    x = Var("x")
    with pytest.raises(ModelError, match="unknown predicate 'nope'"):
        Domain("d", {"p": Predicate("p", 1)}, (Operator("o", (x,), (Precondition(atom("nope", x)),)),))
    with pytest.raises(ModelError, match="takes 1 argument"):
        Domain("d", {"p": Predicate("p", 1)}, (Operator("o", (x,), (), (atom("p", x, x),)),))
    dom = Domain("d", {"p": Predicate("p", 1)})
    with pytest.raises(ModelError, match="goal of"):
        Problem(dom, {}, State(), Goal.of([atom("q", "a")]))


def test_levels_abs_and_next_level():
    x = Var("x")
    op = Operator(
        "op", (x,),
        (Precondition(atom("a", x), 3), Precondition(atom("b", x), 2), Precondition(atom("c", x), 0)),
        (atom("d", x),),
    )
    act = op.instantiate({x: "o"})
    lm = LevelMap(top=2)  # most abstract: keep criticality > 2
    assert act.preconditions(lm.level(act)) == (atom("a", "o"),)
    assert not lm.is_primitive(act)
    lm2 = lm.next_level(act)
    assert lm2.level(act) == 1 and set(act.preconditions(1)) == {atom("a", "o"), atom("b", "o")}
    lm3 = lm2.next_level(act)
    assert lm3.is_primitive(act) and len(act.preconditions(lm3.level(act))) == 3
    assert lm3.next_level(act) == lm3  # nothing more to add
    # another instance of the same operator is untouched by NextLevel
    other = op.instantiate({x: "p"})
    assert lm3.level(other) == 2 and lm3.floor("op") is None
    # a plan below lm3 with an instance of op more abstract than act (refined above it) floors op at
    # act's level; instances of other operators, or as concrete as act, change nothing
    op2 = Operator("op2", (x,), (Precondition(atom("a", x), 3), Precondition(atom("c", x), 0)), (atom("e", x),))
    third = op.instantiate({x: "q"})
    assert lm3.floored([act, op2.instantiate({x: "o"})]) is lm3
    fl = lm3.floored([other, act])
    assert fl.floor("op") == -1 and fl.level(other) == fl.level(third) == -1 and fl.is_primitive(other)
    assert fl.overrides == lm3.overrides and lm.floored([other]) is lm
    assert fl.next_level(op2.instantiate({x: "o"})).floor("op") == -1  # NextLevel keeps the floors
    # an instance of another operator keeps the top level
    assert fl.level(op2.instantiate({x: "o"})) == 2
    # an instance's own level below the floor stands: a map with op's floor at 1 and act at -1
    mixed = LevelMap(2, frozenset({(act.key, -1)}), frozenset({("op", 1)}))
    assert mixed.level(act) == -1 and mixed.level(other) == 1
