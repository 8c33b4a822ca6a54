"""Constructs of the IPC files of benchmarks/results/ipc_check_ipc9.md that nowplan first failed on.

Each test is a small file written here that reproduces the construct of an IPC
domain; every plan replays on the original semantics (tests/pddl_sim.py).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.cli import main
from nowplan.io import pddl_adl
from nowplan.io.pddl_read import load_pddl

from test_pddl_ipc_fixes import solve  # (write the files, plan with the CLI, check the plan)


# IPC-2004 philosophers (promela): the goal is one non-recursive derived atom per process, each defined
# by a disjunction; substituted, the goal's normal form is the product of the disjunctions.
DONE = """\
(define (domain done)
  (:requirements :typing :derived-predicates :negative-preconditions)
  (:types job)
  (:predicates (red ?j - job) (green ?j - job) (blue ?j - job) (finished ?j - job))
  (:derived (finished ?j - job) (or (red ?j) (green ?j) (blue ?j)))
  (:action paint-red :parameters (?j - job) :precondition (not (finished ?j)) :effect (red ?j))
  (:action paint-green :parameters (?j - job) :precondition (not (finished ?j)) :effect (green ?j))
  (:action paint-blue :parameters (?j - job) :precondition (not (finished ?j)) :effect (blue ?j)))
"""


def done_problem(n: int) -> str:
    jobs = " ".join(f"j{i}" for i in range(n))
    goal = " ".join(f"(finished j{i})" for i in range(n))
    return f"(define (problem done-{n}) (:domain done) (:objects {jobs} - job) (:init) (:goal (and {goal})))\n"


def test_a_goal_of_derived_atoms_too_large_to_substitute_is_evaluated_by_rules(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    n = 6  # 3**6 = 729 disjuncts once substituted, over the bound
    assert 3 ** n > pddl_adl.MAX_DISJUNCTS
    (tmp_path / "d.pddl").write_text(DONE)
    (tmp_path / "p.pddl").write_text(done_problem(n))
    prob = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl")
    assert set(prob.domain.derived) == {"finished"}  # kept as a derived predicate, evaluated by rules
    assert [a.predicate for a in prob.goal.atoms] == ["finished"] * n
    steps = solve(tmp_path, DONE, done_problem(n), capsys)
    assert len(steps) == n


def test_a_small_goal_of_derived_atoms_is_still_substituted(tmp_path: Path) -> None:
    (tmp_path / "d.pddl").write_text(DONE)
    (tmp_path / "p.pddl").write_text(done_problem(2))
    prob = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl")
    assert not prob.domain.derived  # substituted: the regression planner and HPN can use the domain


# IPC-1998 ADL files (mystery, mystery prime) are PDDL 1.x: they open with the Lisp directive
# (in-package "PDDL") and bind extra variables with :vars.
PACKAGE = """\
(in-package "PDDL")

(define (domain lamp)
  (:requirements :strips)
  (:predicates (off ?l) (on ?l))
  (:action switch :parameters (?l) :precondition (off ?l) :effect (and (on ?l) (not (off ?l)))))
"""
LAMP_P = "(define (problem lamp-1) (:domain lamp) (:objects a b) (:init (off a) (off b)) (:goal (and (on a) (on b))))\n"


def test_the_lisp_in_package_directive_is_ignored(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert sorted(solve(tmp_path, PACKAGE, LAMP_P, capsys)) == ["(switch a)", "(switch b)"]


def test_lines_after_the_in_package_directive_keep_their_numbers(tmp_path: Path,
                                                                 capsys: pytest.CaptureFixture[str]) -> None:
    bad = PACKAGE.replace("(off ?l) :effect", "(offf ?l) :effect")  # line 6
    (tmp_path / "d.pddl").write_text(bad)
    (tmp_path / "p.pddl").write_text(LAMP_P)
    assert main(["plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"{tmp_path / 'd.pddl'}:6:" in err[0] and "offf" in err[0]


def test_pddl1_vars_are_refused_in_one_line_naming_the_fix(tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    vars_domain = PACKAGE.replace(":parameters (?l) :precondition", ":parameters () :vars (?l) :precondition")
    (tmp_path / "d.pddl").write_text(vars_domain)
    (tmp_path / "p.pddl").write_text(LAMP_P)
    assert main(["plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and ":6:" in err[0] and ":vars" in err[0] and ":parameters" in err[0]


def test_a_long_comment_banner_before_define_reads_in_linear_time(tmp_path: Path,
                                                                  capsys: pytest.CaptureFixture[str]) -> None:
    # IPC-2000 blocks opens with ;;;;...;;;; banner lines: looking for (in-package ...) past them must
    # not backtrack (a regular expression over the comments took minutes on this file)
    banner = (";" * 40 + "\n") + ";;; 4 Op-blocks world\n" + (";" * 40 + "\n") + "\n"
    import time
    t0 = time.process_time()
    steps = solve(tmp_path, banner + PACKAGE.split("\n", 2)[2], LAMP_P, capsys)
    assert sorted(steps) == ["(switch a)", "(switch b)"]
    assert time.process_time() - t0 < 10


def test_comments_may_precede_the_in_package_directive(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    text = ";; mystery, ADL version\n;;;;;;;;;;;;;;;;\n" + PACKAGE
    assert sorted(solve(tmp_path, text, LAMP_P, capsys)) == ["(switch a)", "(switch b)"]


# IPC-2006 trucks: a load needs every area closer to the door free; with a static `closer` the
# (forall (imply ...)) compiles to variants that may also require areas `closer` excuses.
TRUCK = """\
(define (domain truck)
  (:requirements :typing :adl)
  (:types area crate)
  (:predicates (free ?a - area) (closer ?a1 ?a2 - area) (in ?c - crate ?a - area) (ready ?c - crate))
  (:action load
    :parameters (?c - crate ?a1 - area)
    :precondition (and (ready ?c) (free ?a1)
                       (forall (?a2 - area) (imply (closer ?a2 ?a1) (free ?a2))))
    :effect (and (not (free ?a1)) (not (ready ?c)) (in ?c ?a1))))
"""
TRUCK_P = """\
(define (problem truck-1) (:domain truck)
  (:objects c1 c2 c3 - crate a1 a2 a3 - area)
  (:init (free a1) (free a2) (free a3) (closer a1 a2) (closer a1 a3) (closer a2 a3)
         (ready c1) (ready c2) (ready c3))
  (:goal (and (in c1 a3) (in c2 a2) (in c3 a1))))
"""


def test_dominated_variants_of_one_action_instance_are_grounded_once(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from collections import Counter

    from nowplan.planning.task_grounding import clear_cache, grounding

    (tmp_path / "d.pddl").write_text(TRUCK)
    (tmp_path / "p.pddl").write_text(TRUCK_P)
    prob = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl")
    assert len({op.name for op in prob.domain.operators if op.pddl_name == "load"}) > 1  # compiled to variants
    clear_cache()
    g = grounding(prob.domain, prob.objects, prob.init, 0)
    per_instance = Counter((a.operator.pddl_name, a.args) for a in g.actions)
    assert per_instance and max(per_instance.values()) == 1
    assert len(per_instance) == 9  # 3 crates x 3 areas
    # the variant kept needs only the areas `closer` names: a3 (behind a1 and a2) is loaded first, a1 last
    steps = solve(tmp_path, TRUCK, TRUCK_P, capsys)
    assert steps[-1] == "(load c3 a1)"
