"""Constructs of the IPC files of benchmarks/results/ipc_check_ipc14.md that nowplan first handled badly.

Each test is a small file written here that reproduces the construct of an IPC
domain (not the IPC file itself).
"""

from __future__ import annotations

import logging
from pathlib import Path

import pytest

from nowplan.cli import main

# IPC-2004 promela optical telegraph (derived predicates): a goal of non-recursive derived atoms whose
# definitions, substituted, quantify again and again over the objects. Here (bad ?x) is a two-step
# chain out of ?x, and the goal says no object is bad: substituted, 50 x 50 x 50 instances.
CHAINS = """\
(define (domain chains)
  (:requirements :typing :derived-predicates :existential-preconditions :universal-preconditions)
  (:types obj)
  (:predicates (r ?a ?b - obj) (bad ?x - obj))
  (:derived (bad ?x - obj) (exists (?a - obj) (exists (?b - obj) (and (r ?x ?a) (r ?a ?b)))))
  (:action cut :parameters (?a ?b - obj) :precondition (r ?a ?b) :effect (not (r ?a ?b))))
"""
OBJECTS = " ".join(f"o{i}" for i in range(1, 51))
CHAINS_PROBLEM = f"""\
(define (problem chains-50) (:domain chains)
  (:objects {OBJECTS} - obj)
  (:init (r o1 o2) (r o2 o3))
  (:goal (forall (?x - obj) (not (bad ?x)))))
"""


def test_a_blown_up_substitution_is_refused_early_and_the_rules_plan_it(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], caplog: pytest.LogCaptureFixture
) -> None:
    # the substituted goal has ~375,000 nodes: the reader gives up on substituting as soon as it passes
    # MAX_SUBSTITUTED_NODES (it used to build the whole condition first, then meet the DNF bound) and
    # evaluates the derived predicates by rules; the plan cuts one link of the only chain
    (tmp_path / "d.pddl").write_text(CHAINS)
    (tmp_path / "p.pddl").write_text(CHAINS_PROBLEM)
    with caplog.at_level(logging.INFO, logger="nowplan.io.pddl_read"):
        code = main(["plan", str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"), "--time-limit", "20"])
    out = capsys.readouterr().out.splitlines()
    assert code == 0 and out in (["(cut o1 o2)"], ["(cut o2 o3)"])
    fallbacks = [r.getMessage() for r in caplog.records if "by rules instead" in r.getMessage()]
    assert len(fallbacks) == 1 and "nodes in negation normal form" in fallbacks[0], fallbacks
