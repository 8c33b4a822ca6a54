"""Reading PDDL: the supported fragment, the model it gives, and one clear error per bad input."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from nowplan.core.atoms import Atom, Var
from nowplan.errors import ContradictoryGoalError, NowplanError, PDDLError, UnsupportedPDDLError
from nowplan.io.pddl_read import load_pddl, read_domain

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"
DOMAINS = ("logistics", "blocksworld", "gripper", "lights")

GOOD_DOMAIN = """\
(define (domain toy)
  (:requirements :strips :typing :negative-preconditions :equality :action-costs)
  (:types block - thing thing)
  (:constants table - thing)
  (:predicates (on ?x - block ?y - thing) (clear ?x - thing) (marked ?x - block))
  (:functions (total-cost) - number)
  (:action move
    :parameters (?x - block ?y - thing ?z - thing)
    :precondition (and (on ?x ?y) (clear ?x) (clear ?z) (not (= ?y ?z)) (not (marked ?x)))
    :effect (and (on ?x ?z) (not (on ?x ?y)) (clear ?y) (not (clear ?z)) (increase (total-cost) 3)))
  (:action mark
    :parameters (?x - block)
    :precondition (clear ?x)
    :effect (marked ?x)))
"""

GOOD_PROBLEM = """\
(define (problem toy-1) (:domain toy)
  (:objects a b - block)
  (:init (on a table) (on b a) (clear b) (clear table) (= (total-cost) 0))
  (:goal (and (on a b) (not (marked b))))
  (:metric minimize (total-cost)))
"""


def write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def load_texts(tmp_path: Path, domain: str = GOOD_DOMAIN, problem: str = GOOD_PROBLEM):
    return load_pddl(write(tmp_path, "d.pddl", domain), write(tmp_path, "p.pddl", problem))


@pytest.mark.parametrize("name", DOMAINS)
def test_classic_domains_load(name: str) -> None:
    problems = sorted((DATA / name).glob("p*.pddl"))
    assert len(problems) >= 3
    for p in problems:
        prob = load_pddl(DATA / name / "domain.pddl", p)
        assert prob.domain.name == name
        assert prob.domain.top_level == 0  # flat without a criticality file
        assert len(prob.goal) >= 1
        assert all(pre.criticality == 1 for op in prob.domain.operators for pre in op.preconditions)


def test_model_of_the_toy_domain(tmp_path: Path) -> None:
    prob = load_texts(tmp_path)
    d = prob.domain
    assert d.types == {"block": "thing", "thing": None}
    assert d.constants == {"table": "thing"}
    assert [o.name for o in d.operators] == ["move", "mark"]  # file order
    move = d.operator_map["move"]
    x, y, z = Var("x"), Var("y"), Var("z")
    assert move.params == (x, y, z) and move.param_types == ("block", "thing", "thing")
    assert Atom("=", (y, z), False) in [p.atom for p in move.preconditions]
    assert Atom("marked", (x,), False) in [p.atom for p in move.preconditions]
    # deletes first, then adds (PDDL's add-after-delete semantics under State.apply)
    assert [e.value for e in move.effects] == [False, False, True, True]
    assert move.cost == 3.0
    assert d.operator_map["mark"].cost == 0.0  # :action-costs without an increase costs 0
    assert prob.objects == {"a": "block", "b": "block"}
    assert prob.init.holds(Atom("on", ("b", "a")))
    assert prob.init.holds(Atom("=", ("a", "a"))) and not prob.init.holds(Atom("=", ("a", "b")))
    assert prob.goal.atoms == {Atom("on", ("a", "b")), Atom("marked", ("b",), False)}


def test_names_are_case_insensitive(tmp_path: Path) -> None:
    prob = load_texts(tmp_path, GOOD_DOMAIN.replace("(:action move", "(:action MOVE"),
                      GOOD_PROBLEM.replace("(on b a)", "(ON B A)"))
    assert "move" in prob.domain.operator_map
    assert prob.init.holds(Atom("on", ("b", "a")))


def test_untyped_domain_has_no_types() -> None:
    d = read_domain(DATA / "blocksworld" / "domain.pddl")
    assert d.types == {} and all(t is None for o in d.operators for t in o.param_types)


# --------------------------------------------------------------------------- bad input


def test_syntax_error_has_file_and_line(tmp_path: Path) -> None:
    bad = GOOD_DOMAIN.replace("(clear ?x) (clear ?z)", "(clear ?x) ]clear ?z)")
    with pytest.raises(PDDLError) as info:
        load_texts(tmp_path, bad)
    assert info.value.line == 9
    assert str(info.value).startswith(f"{tmp_path / 'd.pddl'}:9: PDDL syntax error")
    assert "\n" not in str(info.value)


def test_unexpected_end_of_file_has_line(tmp_path: Path) -> None:
    with pytest.raises(PDDLError) as info:
        load_texts(tmp_path, GOOD_PROBLEM.rstrip()[:-1] and GOOD_DOMAIN.rstrip()[:-2])
    assert info.value.line is not None and "end of file" in str(info.value)


def test_parser_leaves_tracebacklimit_alone(tmp_path: Path) -> None:
    before = getattr(sys, "tracebacklimit", None)
    with pytest.raises(PDDLError):
        load_texts(tmp_path, "(define (domain x) ]")
    assert getattr(sys, "tracebacklimit", None) == before


@pytest.mark.parametrize(
    "requirement", [":conditional-effects", ":adl", ":disjunctive-preconditions", ":derived-predicates",
                    ":numeric-fluents", ":universal-preconditions", ":durative-actions"],
)
def test_declared_requirements_are_accepted(tmp_path: Path, requirement: str) -> None:
    """A requirement only declares; refusals are for constructs the file uses (issue 18)."""
    text = GOOD_DOMAIN.replace(":action-costs)", f":action-costs {requirement})")
    assert load_texts(tmp_path, text).domain.name == "toy"


def test_unknown_requirement_is_a_warning(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    text = GOOD_DOMAIN.replace(":action-costs)", ":action-costs :made-up)")
    assert load_texts(tmp_path, text).domain.name == "toy"
    assert "unknown requirement :made-up" in caplog.text


def test_numeric_effect_is_refused(tmp_path: Path) -> None:
    effect = "(and (marked ?x) (increase (total-cost) (total-cost)))"
    text = GOOD_DOMAIN.replace(":effect (marked ?x)))", f":effect {effect}))")
    with pytest.raises(UnsupportedPDDLError) as info:
        load_texts(tmp_path, text)
    assert "numeric effect" in str(info.value) and "action mark" in str(info.value)
    assert info.value.line == 14


def test_undeclared_disjunction_is_a_warning(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    text = GOOD_DOMAIN.replace(":precondition (clear ?x)", ":precondition (or (clear ?x) (marked ?x))")
    prob = load_texts(tmp_path, text)
    assert "d.pddl:13: the domain uses :disjunctive-preconditions without declaring it" in caplog.text
    marks = [o for o in prob.domain.operators if o.pddl_name == "mark"]
    assert len(marks) == 2  # one operator per disjunct


def test_unknown_predicate_in_action(tmp_path: Path) -> None:
    text = GOOD_DOMAIN.replace(":precondition (clear ?x)", ":precondition (shiny ?x)")
    with pytest.raises(PDDLError, match=r"unknown predicate 'shiny' in the precondition of action mark") as info:
        load_texts(tmp_path, text)
    assert info.value.line == 13 and str(info.value).startswith(str(tmp_path / "d.pddl"))


def test_unknown_predicate_in_init_and_goal(tmp_path: Path) -> None:
    with pytest.raises(PDDLError, match=r"p\.pddl:3: unknown predicate 'shiny' in the initial state"):
        load_texts(tmp_path, problem=GOOD_PROBLEM.replace("(clear b)", "(shiny b)"))
    with pytest.raises(PDDLError, match=r"p\.pddl:4: unknown predicate 'shiny' in the goal"):
        load_texts(tmp_path, problem=GOOD_PROBLEM.replace("(on a b)", "(shiny a)"))


def test_arity_mismatch(tmp_path: Path) -> None:
    with pytest.raises(PDDLError, match=r"p\.pddl:4: predicate 'on' takes 2 argument\(s\) but the goal gives 1"):
        load_texts(tmp_path, problem=GOOD_PROBLEM.replace("(on a b)", "(on a)"))
    text = GOOD_DOMAIN.replace(":effect (marked ?x)", ":effect (marked ?x ?x)")
    with pytest.raises(PDDLError, match=r"d\.pddl:14: predicate 'marked' takes 1"):
        load_texts(tmp_path, text)


def test_unknown_object_and_type(tmp_path: Path) -> None:
    with pytest.raises(PDDLError, match=r"p\.pddl:4: unknown object 'c' in the goal"):
        load_texts(tmp_path, problem=GOOD_PROBLEM.replace("(on a b)", "(on a c)"))
    with pytest.raises(PDDLError, match=r"unknown type 'brick'"):
        load_texts(tmp_path, problem=GOOD_PROBLEM.replace("a b - block", "a b - brick"))


def test_contradictory_goals(tmp_path: Path) -> None:
    with pytest.raises(ContradictoryGoalError, match=r"p\.pddl: goal is contradictory"):
        load_texts(tmp_path, problem=GOOD_PROBLEM.replace("(not (marked b))", "(not (on a b))"))
    # two places at once contradict the inferred mutex {at[0], in[0]}
    log = DATA / "logistics"
    text = (log / "p01.pddl").read_text().replace("(at pkg2 city1-loc1)", "(at pkg1 city1-loc1)")
    with pytest.raises(ContradictoryGoalError, match="at\\(pkg1"):
        load_pddl(log / "domain.pddl", write(tmp_path, "p.pddl", text))


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(PDDLError, match="nope.pddl: file not found"):
        load_pddl(tmp_path / "nope.pddl", DATA / "gripper" / "p01.pddl")


def test_every_error_is_one_line(tmp_path: Path) -> None:
    cases = [
        GOOD_DOMAIN.replace("(:types", "(:typs"),
        GOOD_DOMAIN.replace("?x - block ?y - thing)", "?x - blok ?y - thing)"),
        GOOD_DOMAIN.replace("(:constants table - thing)", "").replace(
            ":precondition (clear ?x)", ":precondition (clear table)"
        ),
    ]
    for text in cases:
        with pytest.raises(NowplanError) as info:
            load_texts(tmp_path, text)
        assert "\n" not in str(info.value)
        assert str(tmp_path / "d.pddl") in str(info.value)
