"""Type sets from static unary predicates in the automatic hierarchy (issue 18, target 2).

Untyped STRIPS domains (IPC driverlog, logistics-98/00, mystery) state an argument's kind as a
static unary precondition; read as a type, it separates a package's ``at`` from a truck's and
gives the hierarchy a level per kind, as typed logistics has.  A problem in which one object has
two such kinds gets the hierarchy without them."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.cli import main
from nowplan.core.atoms import Atom
from nowplan.io.pddl_read import load_pddl, read_domain
from nowplan.planning.abstraction import derive_hierarchy, literal_levels, violations
from nowplan.planning.problem_hierarchy import goal_stages, prepare_problem, problem_hierarchy

DOMAIN = """(define (domain dl) (:requirements :strips)
 (:predicates (at ?x ?l) (in ?o ?t) (driving ?d ?t) (empty ?t) (link ?x ?y)
              (obj ?o) (truck ?t) (driver ?d) (location ?l))
 (:action load :parameters (?o ?t ?l)
  :precondition (and (obj ?o) (truck ?t) (location ?l) (at ?t ?l) (at ?o ?l))
  :effect (and (not (at ?o ?l)) (in ?o ?t)))
 (:action unload :parameters (?o ?t ?l)
  :precondition (and (obj ?o) (truck ?t) (location ?l) (at ?t ?l) (in ?o ?t))
  :effect (and (not (in ?o ?t)) (at ?o ?l)))
 (:action board :parameters (?d ?t ?l)
  :precondition (and (driver ?d) (truck ?t) (location ?l) (at ?t ?l) (at ?d ?l) (empty ?t))
  :effect (and (not (at ?d ?l)) (driving ?d ?t) (not (empty ?t))))
 (:action drive :parameters (?t ?a ?b ?d)
  :precondition (and (truck ?t) (location ?a) (location ?b) (driver ?d) (at ?t ?a)
                     (driving ?d ?t) (link ?a ?b))
  :effect (and (not (at ?t ?a)) (at ?t ?b))))
"""

PROBLEM = """(define (problem p) (:domain dl)
 (:objects pkg t1 d1 s0 s1)
 (:init (obj pkg) (truck t1) (driver d1) (location s0) (location s1) (link s0 s1) (link s1 s0)
        (at pkg s0) (at t1 s0) (at d1 s0) (empty t1) %s)
 (:goal (and (at pkg s1) (at t1 s0))))
"""


def _files(tmp_path: Path, extra: str = "") -> tuple[Path, Path]:
    d, p = tmp_path / "domain.pddl", tmp_path / "p.pddl"
    d.write_text(DOMAIN)
    p.write_text(PROBLEM % extra)
    return d, p


def test_type_predicates_put_packages_above_vehicles(tmp_path: Path) -> None:
    d, _ = _files(tmp_path)
    domain = read_domain(d)
    h = derive_hierarchy(domain)
    assert h.type_sets and h.top == 1
    levels = {str(c): lvl for lvl, cs in h.by_level().items() for c in cs}
    assert levels["at([obj], [location])"] == levels["in([obj], [truck])"] == 1
    assert levels["at([truck], [location])"] == levels["driving([driver], [truck])"] == 0
    assert violations(domain, literal_levels(domain, h)) == []
    plain = derive_hierarchy(domain, type_sets=False)
    assert not plain.type_sets and plain.top == 0  # every `at` one class: one level, as before


def test_a_problem_checks_its_objects_and_stages_the_package_first(tmp_path: Path) -> None:
    d, p = _files(tmp_path)
    prob = load_pddl(d, p, "auto")
    assert problem_hierarchy(prob).top == 1
    (stage,) = goal_stages(prob, problem_hierarchy(prob))
    assert stage.atoms == frozenset({Atom("at", ("pkg", "s1"))})
    assert prepare_problem(prob).stages == (stage,)


def test_an_object_with_two_kinds_gets_the_hierarchy_without_type_sets(tmp_path: Path) -> None:
    d, p = _files(tmp_path, "(obj t1)")  # t1 is a truck and a package: at(t1, _) is in two classes
    prob = load_pddl(d, p, "auto")
    assert problem_hierarchy(prob).top == 0
    assert {pre.criticality for op in prob.domain.operators for pre in op.preconditions} == {1}
    assert prepare_problem(prob).stages == ()


def test_cli_runs_the_two_level_hierarchy_to_the_goal(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    d, p = _files(tmp_path)
    assert main(["criticality", str(d)]) == 0
    assert "# level 1 (criticality 2): at([obj], [location])" in capsys.readouterr().out
    assert main(["run", str(d), str(p), "--criticality", "auto", "--strategy", "hpn"]) == 0
    assert "reached" in capsys.readouterr().out
