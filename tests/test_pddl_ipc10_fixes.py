"""Constructs of the IPC files of benchmarks/results/ipc_check_ipc10.md that nowplan first failed on.

Each test is a small file written here that reproduces the construct of an IPC
domain, and checks the plan's steps (the construct's reading is the point).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.cli import main

# IPC-2000 elevator, full ADL (the competition's original file): quantifiers and parameters typed by
# unary predicates, (exists (?p - conflict_A) ...), (forall (?p - vip) (served ?p)).
LIFT = """\
(define (domain lift)
  (:requirements :adl)
  (:types person)
  (:predicates (vip ?p - person) (served ?p - person) (closed) (thanked ?p - person))
  (:action serve :parameters (?p - person) :precondition (not (served ?p)) :effect (served ?p))
  (:action close :parameters () :precondition (forall (?p - vip) (served ?p)) :effect (closed))
  (:action reset :parameters () :precondition (exists (?q - vip) (served ?q))
    :effect (forall (?p - vip) (not (served ?p))))
  (:action thank :parameters (?p - vip) :precondition (served ?p) :effect (thanked ?p)))
"""


def lift_problem(init: str, goal: str) -> str:
    return f"(define (problem l) (:domain lift) (:objects a b - person) (:init (vip a) {init}) (:goal {goal}))\n"


def plan(tmp_path: Path, domain: str, problem: str, capsys: pytest.CaptureFixture[str]) -> tuple[int, list[str], str]:
    (tmp_path / "d.pddl").write_text(domain)
    (tmp_path / "p.pddl").write_text(problem)
    code = main(["plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"), "--time-limit", "20"])
    out = capsys.readouterr()
    return code, out.out.splitlines(), out.err


def test_a_forall_over_a_predicate_type_ranges_over_the_objects_it_holds_of(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], caplog: pytest.LogCaptureFixture) -> None:
    code, steps, err = plan(tmp_path, LIFT, lift_problem("", "(closed)"), capsys)
    assert code == 0, err
    assert steps == ["(serve a)", "(close)"]  # a is the only vip; b need not be served (empty type: just close)
    assert "the predicate 'vip' as its type" in caplog.text


def test_exists_and_a_forall_effect_over_a_predicate_type(tmp_path: Path,
                                                          capsys: pytest.CaptureFixture[str]) -> None:
    # reset deletes (served a) only: deleting (served b) too would need (serve b) again
    code, steps, err = plan(tmp_path, LIFT, lift_problem("(served a) (served b)",
                                                         "(and (not (served a)) (served b))"), capsys)
    assert code == 0, err
    assert steps == ["(reset)"]


def test_a_parameter_of_a_predicate_type_takes_only_the_objects_it_holds_of(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    code, steps, _ = plan(tmp_path, LIFT, lift_problem("(served a)", "(thanked a)"), capsys)
    assert code == 0 and steps == ["(thank a)"]
    code, _, _ = plan(tmp_path, LIFT, lift_problem("(served b)", "(thanked b)"), capsys)
    assert code == 1  # b is no vip: unsolvable


def test_a_type_that_is_neither_declared_nor_a_unary_predicate_is_still_unknown(tmp_path: Path,
                                                            capsys: pytest.CaptureFixture[str]) -> None:
    code, _, err = plan(tmp_path, LIFT.replace("(?p - vip) (served ?p)) :effect (closed)",
                                               "(?p - guest) (served ?p)) :effect (closed)"),
                        lift_problem("", "(closed)"), capsys)
    assert code == 2
    assert "unknown type 'guest'" in err and "d.pddl:6" in err
