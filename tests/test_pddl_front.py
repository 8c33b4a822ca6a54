"""The lenient PDDL front end: each accepted construct, each refusal, the type checks, the ADL bounds."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from nowplan.cli import main
from nowplan.core.atoms import Atom, Var
from nowplan.errors import NowplanError, PDDLError, UnsupportedPDDLError
from nowplan.io import pddl_adl
from nowplan.io.pddl_read import load_pddl, read_domain
from nowplan.io.sexpr import parse_sexprs

from pddl_sim import check_plan

DOMAIN = """\
(define (domain shop)
  (:requirements :strips :typing)
  (:types item - object box)
  (:constants crate - box)
  (:predicates (in ?i - item ?b - box) (free ?i - item) (sealed ?b - box) (shiny ?i - item))
  (:action pack
    :parameters (?i - item ?b - box)
    :precondition (and (free ?i) (not (sealed ?b)))
    :effect (and (in ?i ?b) (not (free ?i))))
  (:action seal
    :parameters (?b - box)
    :precondition (and)
    :effect (sealed ?b)))
"""

PROBLEM = """\
(define (problem shop-1) (:domain shop)
  (:objects a b - item bin - box)
  (:init (free a) (free b))
  (:goal (and (in a crate) (in b bin) (sealed crate))))
"""


def write(tmp_path: Path, domain: str, problem: str) -> tuple[Path, Path]:
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    d.write_text(domain)
    p.write_text(problem)
    return d, p


def load(tmp_path: Path, domain: str = DOMAIN, problem: str = PROBLEM):  # type: ignore[no-untyped-def]
    return load_pddl(*write(tmp_path, domain, problem))


def solve(tmp_path: Path, domain: str, problem: str, capsys: pytest.CaptureFixture[str]) -> list[str]:
    d, p = write(tmp_path, domain, problem)
    code = main(["plan", str(d), str(p), "--time-limit", "20"])
    out = capsys.readouterr().out.splitlines()
    assert code == 0, out
    check_plan(domain, problem, out)  # the plan replays on the original semantics
    return out


# --------------------------------------------------------------------------- tokenizer


def test_tokens_keep_lines_and_comments_are_skipped() -> None:
    (top,) = parse_sexprs("; c\n(A (b ?X)\n ; (c)\n  D)")
    assert str(top) == "(a (b ?x) d)" and top.line == 2 and top.items[2].line == 4  # type: ignore[union-attr]


@pytest.mark.parametrize(("text", "what", "line"), [
    ("(a\n(b", "never closed", 2), ("(a))", "unexpected ')'", 1), ("(a\n [b])", "unexpected character '['", 2),
])
def test_tokenizer_errors(text: str, what: str, line: int) -> None:
    with pytest.raises(PDDLError, match=re.escape(what)) as info:
        parse_sexprs(text, "f.pddl")
    assert info.value.line == line


def test_deep_nesting_is_refused_not_a_recursion_error() -> None:
    with pytest.raises(PDDLError, match="nested deeper"):
        parse_sexprs("(" * 5000)


# --------------------------------------------------------------------------- accepted constructs


def test_upper_case_everywhere(tmp_path: Path) -> None:
    prob = load(tmp_path, DOMAIN.upper(), PROBLEM.upper())
    assert prob.domain.name == "shop" and prob.goal.atoms == load(tmp_path).goal.atoms


def test_object_in_types_and_constants(tmp_path: Path) -> None:
    prob = load(tmp_path, DOMAIN.replace("(:types item - object box)", "(:types object item - object box - object)"))
    assert prob.domain.types == {"item": None, "box": None}
    assert prob.domain.constants == {"crate": "box"}


def test_parent_type_declared_only_as_parent(tmp_path: Path) -> None:
    prob = load(tmp_path, DOMAIN.replace("(:types item - object box)", "(:types item - thing box - thing)"))
    assert prob.domain.types == {"item": "thing", "box": "thing", "thing": None}


def test_either_parameter_gives_one_operator_per_type(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dom = DOMAIN.replace("(shiny ?i - item)", "(shiny ?i - (either item box))").replace(
        "(:action seal", "(:action polish :parameters (?x - (either item box)) :effect (shiny ?x))\n  (:action seal")
    prob = load(tmp_path, dom, PROBLEM.replace("(sealed crate)", "(sealed crate) (shiny bin) (shiny a)"))
    polish = [o for o in prob.domain.operators if o.pddl_name == "polish"]
    assert sorted(o.param_types for o in polish) == [("box",), ("item",)]
    plan = solve(tmp_path, dom, PROBLEM.replace("(sealed crate)", "(sealed crate) (shiny bin) (shiny a)"), capsys)
    assert "(polish bin)" in plan and "(polish a)" in plan


def test_total_cost_without_the_requirement_and_static_function_costs(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dom = DOMAIN.replace("(:action pack", "(:functions (weight ?i - item) (total-cost))\n  (:action pack").replace(
        "(not (free ?i))))", "(not (free ?i)) (increase (total-cost) (* 2 (weight ?i)))))")
    prob_text = PROBLEM.replace("(free b))", "(free b) (= (weight a) 3) (= (weight b) 4) (= (total-cost) 0))")
    prob = load(tmp_path, dom, prob_text)
    pack = prob.domain.operator_map["pack"]
    assert pack.instantiate({Var("i"): "b", Var("b"): "bin"}).cost() == 8.0
    assert prob.domain.operator_map["seal"].cost == 0.0  # costs are used: no increase costs 0
    d, p = write(tmp_path, dom, prob_text)
    assert main(["plan", str(d), str(p), "--json"]) == 0
    import json

    doc = json.loads(capsys.readouterr().out)
    assert doc["cost"] == 14.0 == check_plan(dom, prob_text, doc["plan"])


def test_missing_function_value_is_named(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dom = DOMAIN.replace("(:action pack", "(:functions (weight ?i - item))\n  (:action pack").replace(
        "(not (free ?i))))", "(not (free ?i)) (increase (total-cost) (weight ?i))))")
    d, p = write(tmp_path, dom, PROBLEM.replace("(free b))", "(free b) (= (weight a) 3))"))
    code = main(["plan", str(d), str(p)])
    err = capsys.readouterr().err
    assert code == 2 and "gives no value for (weight b)" in err and err.count("\n") == 1, err
    assert f"{p}: " in err


def test_disjunctive_goal_gets_an_auxiliary_action_not_printed(tmp_path: Path,
                                                               capsys: pytest.CaptureFixture[str]) -> None:
    prob = PROBLEM.replace("(:goal (and (in a crate) (in b bin) (sealed crate)))",
                           "(:goal (or (and (in a crate) (sealed bin) (sealed crate)) (in b bin)))")
    plan = solve(tmp_path, DOMAIN, prob, capsys)
    assert plan == ["(pack b bin)"]


def test_quantified_goal_and_forall_effect(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dom = DOMAIN.replace("(:requirements :strips :typing)", "(:requirements :adl)").replace(
        ":effect (sealed ?b)))",
        ":effect (and (sealed ?b) (forall (?i - item) (when (in ?i ?b) (shiny ?i))))))")
    prob = PROBLEM.replace("(:goal (and (in a crate) (in b bin) (sealed crate)))",
                           "(:goal (forall (?i - item) (and (shiny ?i) (exists (?b - box) (in ?i ?b)))))")
    plan = solve(tmp_path, dom, prob, capsys)
    assert sum(s.startswith("(pack") for s in plan) == 2


def test_false_static_goal_is_unsolvable_not_an_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dom = DOMAIN.replace("(shiny ?i - item))", "(shiny ?i - item) (heavy ?i - item))")
    d, p = write(tmp_path, dom, PROBLEM.replace("(:goal (and", "(:goal (and (or (heavy a) (heavy b))"))
    assert main(["plan", str(d), str(p)]) == 1


# --------------------------------------------------------------------------- refusals


@pytest.mark.parametrize(("old", "new", "what"), [
    ("(:action seal", "(:durative-action seal", "durative actions"),
    (":effect (sealed ?b)", ":effect (and (sealed ?b) (increase (stock ?b) 1))", "numeric effect"),
    (":precondition (and)", ":precondition (> (stock ?b) 1)", "numeric condition"),
    (":effect (sealed ?b)", ":effect (oneof (sealed ?b) (and))", "non-deterministic effect"),
    (":effect (sealed ?b)", ":effect (at end (sealed ?b))", "temporal effect"),
    ("(:action seal", "(:derived (shiny ?i - item) (or (free ?i) (exists (?j - item) (and (not (shiny ?j)) "
                      "(in ?j crate)))))\n  (:action seal",
     "the derived predicates are not stratifiable: shiny depends on (not shiny)"),
])
def test_refusals_name_the_construct_and_line(tmp_path: Path, old: str, new: str, what: str) -> None:
    dom = DOMAIN.replace("(:action pack", "(:functions (stock ?b - box))\n  (:action pack").replace(old, new)
    with pytest.raises(UnsupportedPDDLError, match=re.escape(what)) as info:
        load(tmp_path, dom)
    assert info.value.line is not None and "\n" not in str(info.value)
    assert str(info.value).startswith(str(tmp_path / "d.pddl"))


def test_other_metric_is_refused(tmp_path: Path) -> None:
    with pytest.raises(UnsupportedPDDLError, match="metric") as info:
        load(tmp_path, problem=PROBLEM.replace("(sealed crate)))", "(sealed crate)))\n (:metric maximize (total-cost))"))
    assert info.value.line == 5


def test_conditional_effect_bound(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(pddl_adl, "MAX_CONDITIONS", 1)
    dom = DOMAIN.replace(":effect (sealed ?b)))",
                         ":effect (and (when (sealed ?b) (sealed crate)) (when (sealed crate) (sealed ?b)))))")
    with pytest.raises(UnsupportedPDDLError, match=r"action seal has 2 distinct effect conditions.*2\*\*2"):
        read_domain(write(tmp_path, dom, PROBLEM)[0])
    monkeypatch.setattr(pddl_adl, "MAX_CONDITIONS", 2)
    assert len([o for o in read_domain(write(tmp_path, dom, PROBLEM)[0]).operators if o.pddl_name == "seal"]) == 3


def test_dnf_bound(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(pddl_adl, "MAX_DISJUNCTS", 3)
    dom = """(define (domain d) (:predicates (p) (q) (r) (s) (done))
      (:action a :parameters () :precondition (and (or (p) (q)) (or (r) (s))) :effect (done)))"""
    with pytest.raises(UnsupportedPDDLError, match=r"action a has 4 disjuncts .*\(bound 3\)"):
        read_domain(write(tmp_path, dom, PROBLEM)[0])
    monkeypatch.setattr(pddl_adl, "MAX_DISJUNCTS", 4)
    assert len(read_domain(write(tmp_path, dom, PROBLEM)[0]).operators) == 4


def test_quantifier_in_a_domain_alone_needs_a_problem(tmp_path: Path) -> None:
    dom = DOMAIN.replace(":precondition (and)", ":precondition (forall (?i - item) (free ?i))")
    with pytest.raises(UnsupportedPDDLError, match="read the domain together with a problem"):
        read_domain(write(tmp_path, dom, PROBLEM)[0])
    assert load(tmp_path, dom).domain.operator_map["seal"].preconditions  # compiled over a, b


# --------------------------------------------------------------------------- type checks


@pytest.mark.parametrize(("problem_old", "problem_new", "line", "what"), [
    ("(free a)", "(free bin)", 3, "the object 'bin' of type box cannot be argument 1 of 'free' (type item) in the "
                                  "initial state"),
    ("(in b bin)", "(in bin b)", 4, "the object 'bin' of type box cannot be argument 1 of 'in'"),
    ("(in b bin)", "(in b)", 4, "predicate 'in' takes 2 argument(s) but the goal gives 1"),
    ("(free a)", "(free zed)", 3, "unknown object 'zed' in the initial state"),
    ("a b - item", "a b - itme", 2, "unknown type 'itme' in the object 'a'"),
])
def test_problem_type_errors(tmp_path: Path, problem_old: str, problem_new: str, line: int, what: str,
                             capsys: pytest.CaptureFixture[str]) -> None:
    d, p = write(tmp_path, DOMAIN, PROBLEM.replace(problem_old, problem_new, 1))
    code = main(["plan", str(d), str(p)])
    err = capsys.readouterr().err
    assert code == 2 and err.count("\n") == 1, err
    assert f"{p}:{line}: {what}" in err


@pytest.mark.parametrize(("old", "new", "line", "what"), [
    ("(in ?i ?b) (not", "(in ?b ?i) (not", 9, "the variable ?b of type box cannot be argument 1 of 'in'"),
    ("(free ?i) (not", "(free crate) (not", 8, "the object 'crate' of type box cannot be argument 1 of 'free'"),
    ("(free ?i) (not", "(free ?j) (not", 8, "uses the variable ?j, which is not a parameter"),
    ("(?b - box)", "(?b - crate)", 11, "unknown type 'crate'"),
    ("(sealed ?b - box)", "(sealed ?b - boxes)", 5, "unknown type 'boxes' in the predicate sealed"),
])
def test_domain_type_errors(tmp_path: Path, old: str, new: str, line: int, what: str) -> None:
    with pytest.raises(PDDLError) as info:
        load(tmp_path, DOMAIN.replace(old, new, 1))
    assert str(info.value).startswith(f"{tmp_path / 'd.pddl'}:{line}: ") and what in str(info.value)


def test_subtype_objects_fit(tmp_path: Path) -> None:
    dom = DOMAIN.replace("(:types item - object box)", "(:types item - object box gem - item)")
    prob = load(tmp_path, dom, PROBLEM.replace("a b - item", "a - gem b - item"))
    assert prob.init.holds(Atom("free", ("a",)))


def test_same_domain_different_function_values_in_one_process(tmp_path: Path,
                                                              capsys: pytest.CaptureFixture[str]) -> None:
    """Planner caches keyed by the domain must not mix up two problems' action costs."""
    import json

    dom = DOMAIN.replace("(:action pack", "(:functions (weight ?i - item))\n  (:action pack").replace(
        "(not (free ?i))))", "(not (free ?i)) (increase (total-cost) (weight ?i))))")
    costs = []
    for wa, wb in ((3, 4), (10, 20)):
        d, p = write(tmp_path, dom, PROBLEM.replace("(free b))", f"(free b) (= (weight a) {wa}) (= (weight b) {wb}))"))
        assert main(["plan", str(d), str(p), "--json"]) == 0
        costs.append(json.loads(capsys.readouterr().out)["cost"])
    assert costs == [7.0, 30.0]


def test_derived_predicates_are_inlined(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    dom = DOMAIN.replace("(shiny ?i - item))", "(shiny ?i - item) (done) (stored ?i - item))").replace(
        "(:action seal", "(:derived (stored ?i - item) (exists (?b - box) (in ?i ?b)))\n"
        "  (:derived (done) (forall (?i - item) (stored ?i)))\n"
        "  (:action ring :parameters (?b - box) :precondition (and (done) (not (sealed ?b))) :effect (sealed ?b))\n"
        "  (:action seal")
    prob = PROBLEM.replace("(:goal (and (in a crate) (in b bin) (sealed crate)))",
                           "(:goal (and (done) (not (stored b)) (stored a)))")
    d, p = write(tmp_path, dom, prob)
    assert main(["plan", str(d), str(p)]) == 1  # done needs b stored, the goal b not stored: unsolvable
    capsys.readouterr()
    plan = solve(tmp_path, dom, PROBLEM.replace("(:goal (and (in a crate) (in b bin) (sealed crate)))",
                                                "(:goal (and (done) (stored b)))"), capsys)
    assert len(plan) == 2 and all(s.startswith("(pack") for s in plan)


def test_derived_predicate_in_an_effect_is_an_error(tmp_path: Path) -> None:
    dom = DOMAIN.replace("(:action seal", "(:derived (shiny ?i - item) (free ?i))\n  (:action seal").replace(
        ":effect (sealed ?b)", ":effect (and (sealed ?b) (shiny crate))")
    with pytest.raises(PDDLError, match="derived predicate shiny is changed by an action's effect"):
        load(tmp_path, dom)


def test_criticality_rules_name_the_pddl_action_of_compiled_operators(tmp_path: Path) -> None:
    dom = DOMAIN.replace(":precondition (and (free ?i) (not (sealed ?b)))",
                         ":precondition (and (free ?i) (or (sealed crate) (not (sealed ?b))))")
    d, p = write(tmp_path, dom, PROBLEM)
    crit = tmp_path / "c.crit"
    crit.write_text("default 2\npack free 3\n")
    prob = load_pddl(d, p, crit)
    packs = [o for o in prob.domain.operators if o.pddl_name == "pack"]
    assert len(packs) == 2
    assert all(pre.criticality == (3 if pre.atom.predicate == "free" else 2) for o in packs for pre in o.preconditions)


def test_function_costs_are_written_back(tmp_path: Path) -> None:
    from nowplan.io.pddl_write import write_pddl

    corpus = Path(__file__).resolve().parent / "data" / "pddl_ipc_style"
    prob = load_pddl(corpus / "transport-domain.pddl", corpus / "transport-p01.pddl")
    d, p = write_pddl(prob, tmp_path / "out")
    assert "(increase (total-cost) (road-length ?l1 ?l2))" in d.read_text()
    assert "(= (road-length city-loc-1 city-loc-3) 10)" in p.read_text()
    again = load_pddl(d, p)
    b = {Var("v"): "truck-1", Var("l1"): "city-loc-3", Var("l2"): "city-loc-2"}
    assert again.domain.operator_map["drive"].instantiate(b).cost() == 12.0


def test_many_effect_conditions_are_compiled_per_binding(monkeypatch: pytest.MonkeyPatch) -> None:
    from nowplan.io import pddl_actions

    corpus = Path(__file__).resolve().parent / "data" / "pddl_ipc_style"
    files = (corpus / "miconic-adl-domain.pddl", corpus / "miconic-adl-p01.pddl")
    prob = load_pddl(*files)
    stops = [o for o in prob.domain.operators if o.pddl_name == "stop"]
    assert stops and all(o.preconditions[0].atom.predicate == "=" for o in stops)  # (= ?f fN) pins ?f
    # lifted, the 6 passengers give 12 effect conditions (> 10); per floor only 2-4 are left
    assert {o.preconditions[0].atom.args[1] for o in stops} == {"f0", "f1", "f2", "f3"}
    monkeypatch.setattr(pddl_actions, "MAX_BINDINGS", 3)
    with pytest.raises(UnsupportedPDDLError, match=r"12 distinct effect conditions.*4 bindings \(bound 3\)"):
        load_pddl(*files)


def test_ground_equalities_in_the_goal_are_evaluated(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    plan = solve(tmp_path, DOMAIN, PROBLEM.replace("(sealed crate)))", "(sealed crate) (not (= a b))))"), capsys)
    assert "(seal crate)" in plan
    d, p = write(tmp_path, DOMAIN, PROBLEM.replace("(sealed crate)))", "(sealed crate) (= a b)))"))
    assert main(["plan", str(d), str(p)]) == 1  # false in every state: unsolvable


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "x"])
def test_function_values_must_be_finite_numbers(tmp_path: Path, value: str) -> None:
    dom = DOMAIN.replace("(:action pack", "(:functions (weight ?i - item))\n  (:action pack").replace(
        "(not (free ?i))))", "(not (free ?i)) (increase (total-cost) (weight ?i))))")
    with pytest.raises(PDDLError, match="must be a finite number") as info:
        load(tmp_path, dom, PROBLEM.replace("(free b))", f"(free b) (= (weight a) {value}))"))
    assert info.value.line == 3
    with pytest.raises(PDDLError, match="not a finite number"):
        load(tmp_path, dom.replace("(weight ?i))))", "(* inf (weight ?i)))))"))


def test_byte_order_mark_crlf_and_latin1_comments(tmp_path: Path) -> None:
    d, p = write(tmp_path, DOMAIN, PROBLEM)
    d.write_bytes(b"\xef\xbb\xbf" + DOMAIN.replace("\n", "\r\n").encode())
    p.write_bytes(b"; auteur: J\xe9r\xf4me\n" + PROBLEM.encode())
    assert load_pddl(d, p).domain.name == "shop"
