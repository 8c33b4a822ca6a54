"""Abstract actions carry an estimate of their hidden preconditions' cost (planning/hidden_costs.py;
benchmarks/results/auto_ipc/hidden_costs/: IPC transport p01 under auto-HPN, 6,822 -> 1,312)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from nowplan.cli import main
from nowplan.planning.hidden_costs import add_hidden_costs, hmax_costs

# IPC-2008 transport's domain (road lengths as action costs), as the competition files state it
TRANSPORT = """
(define (domain transport) (:requirements :typing :action-costs)
 (:types location target locatable - object vehicle package - locatable capacity-number - object)
 (:predicates (capacity ?v - vehicle ?s1 - capacity-number) (road ?l1 ?l2 - location)
  (at ?x - locatable ?v - location) (capacity-predecessor ?s1 ?s2 - capacity-number)
  (in ?x - package ?v - vehicle))
 (:functions (total-cost) - number (road-length ?l1 ?l2 - location) - number)
 (:action drive :parameters (?v - vehicle ?l1 ?l2 - location)
  :precondition (and (at ?v ?l1) (road ?l1 ?l2))
  :effect (and (not (at ?v ?l1)) (at ?v ?l2) (increase (total-cost) (road-length ?l1 ?l2))))
 (:action drop :parameters (?v - vehicle ?l - location ?p - package ?s1 ?s2 - capacity-number)
  :precondition (and (at ?v ?l) (in ?p ?v) (capacity-predecessor ?s1 ?s2) (capacity ?v ?s1))
  :effect (and (not (in ?p ?v)) (at ?p ?l) (capacity ?v ?s2) (not (capacity ?v ?s1))
               (increase (total-cost) 1)))
 (:action pick-up :parameters (?v - vehicle ?l - location ?p - package ?s1 ?s2 - capacity-number)
  :precondition (and (at ?v ?l) (at ?p ?l) (capacity-predecessor ?s1 ?s2) (capacity ?v ?s2))
  :effect (and (not (at ?p ?l)) (in ?p ?v) (capacity ?v ?s1) (not (capacity ?v ?s2))
               (increase (total-cost) 1))))
"""

# a road a-b-c-d-e of length 10 per leg, a truck at each end, a package near each
LINE = """
(define (problem line) (:domain transport)
 (:objects a b c d e - location truck-1 truck-2 - vehicle package-1 package-2 - package
  capacity-0 capacity-1 capacity-2 - capacity-number)
 (:init (= (total-cost) 0)
  (capacity-predecessor capacity-0 capacity-1) (capacity-predecessor capacity-1 capacity-2)
  (road a b) (= (road-length a b) 10) (road b a) (= (road-length b a) 10)
  (road b c) (= (road-length b c) 10) (road c b) (= (road-length c b) 10)
  (road c d) (= (road-length c d) 10) (road d c) (= (road-length d c) 10)
  (road d e) (= (road-length d e) 10) (road e d) (= (road-length e d) 10)
  (at truck-1 a) (capacity truck-1 capacity-2) (at truck-2 e) (capacity truck-2 capacity-2)
  (at package-1 d) (at package-2 b))
 (:goal (and (at package-1 e) (at package-2 a))))
"""


def test_hmax_is_the_cheapest_relaxed_cost_of_the_hardest_condition() -> None:
    # facts 0..3; a0: 0 -> 1 (cost 5), a1: 1 -> 2 (cost 2), a2: 0 -> 2 (cost 9), a3: {1, 2} -> 3 (cost 1)
    pre = [(0,), (1,), (0,), (1, 2)]
    add = [(1,), (2,), (2,), (3,)]
    h = hmax_costs(5, frozenset({0}), pre, add, [5.0, 2.0, 9.0, 1.0])
    assert h[:4] == [0.0, 5.0, 7.0, 8.0]
    assert h[4] == math.inf


def test_only_hidden_preconditions_add_to_a_cost() -> None:
    # action 3 hides fact 2 at this level (its full row needs it), the others hide nothing
    full = [(0,), (1,), (0,), (1, 2)]
    pre = [(0,), (1,), (0,), (1,)]
    add = [(1,), (2,), (2,), (3,)]
    out = add_hidden_costs(4, frozenset({0}), pre, full, add, [5.0, 2.0, 9.0, 1.0])
    assert out == [5.0, 2.0, 9.0, 1.0 + 7.0]
    assert add_hidden_costs(4, frozenset({0}), full, full, add, [5.0, 2.0, 9.0, 1.0]) is None
    # an unreachable hidden condition, or one the task does not index (-1), adds nothing
    assert add_hidden_costs(4, frozenset({0}), [(), ()], [(3,), (-1,)], [(), ()], [1.0, 1.0]) == [1.0, 1.0]


def _run(tmp_path: Path, capsys: pytest.CaptureFixture[str], *args: str) -> dict[str, object]:
    d, p = tmp_path / "domain.pddl", tmp_path / "p.pddl"
    d.write_text(TRANSPORT)
    p.write_text(LINE)
    assert main([args[0], str(d), str(p), "--json", *args[1:]]) == 0
    out: dict[str, object] = json.loads(capsys.readouterr().out)
    return out


def test_auto_hpn_hands_each_package_to_the_truck_near_it(tmp_path: Path,
                                                           capsys: pytest.CaptureFixture[str]) -> None:
    """Without the estimate the top level (the trucks' positions hidden) handed the packages to trucks
    wherever they stood and the refinements swapped in sibling drops: 48 actions, cost 372, where
    flat planning's first plan takes 8 actions, cost 44 (each truck fetches the package near it)."""
    flat = _run(tmp_path, capsys, "plan", "--improve", "0")
    run = _run(tmp_path, capsys, "run", "--criticality", "auto", "--strategy", "hpn")
    assert run["outcome"] == "reached"
    assert isinstance(flat["cost"], float) and isinstance(run["execution_cost"], float)
    assert run["execution_cost"] <= flat["cost"]
    assert run["actions"] == len(flat["plan"])  # type: ignore[arg-type]


def test_hidden_costs_are_asked_of_the_domains_costs(tmp_path: Path) -> None:
    """Only a domain whose operators do not all cost the same gets the estimate (planning/task.py
    ``varied_costs``): transport's road lengths (a cost read from the arguments) do, gripper's unit
    costs do not."""
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.hidden_costs import varied_costs

    d, p = tmp_path / "domain.pddl", tmp_path / "p.pddl"
    d.write_text(TRANSPORT)
    p.write_text(LINE)
    assert varied_costs(load_pddl(d, p).domain)
    grip = Path(__file__).resolve().parents[1] / "benchmarks" / "classical" / "gripper"
    assert not varied_costs(load_pddl(grip / "domain.pddl", grip / "p01.pddl").domain)
