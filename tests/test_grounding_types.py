"""Grounding's join checks a parameter's type as soon as a condition binds it.

A condition shared by several types (logistics' ``at`` of packages and of
vehicles) used to bind every fact and drop the wrong types only at the end;
the early check must drop exactly those.  Reference: a brute-force
relaxed-reachability fixpoint over every type-consistent binding of every
operator, on the checked-in classical instances (small enough to enumerate).
"""

from __future__ import annotations

import itertools
from pathlib import Path

import pytest

from nowplan.core.atoms import Atom
from nowplan.core.operators import Action
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import task_grounding
from nowplan.planning.task_grounding import _objects_by_type, grounding

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
DOMAINS = ["logistics", "zenotravel", "driverlog", "depots", "miconic", "satellite", "gripper", "barman",
           "rovers", "blocksworld", "nomystery", "visitall", "floortile"]


def brute_force(domain, objects, init: set[Atom], level: int) -> set[tuple[str, tuple[str, ...]]]:
    """Every binding of every operator whose joined conditions (static, or kept at ``level``) are
    relaxed-reachable and whose negative static conditions hold, by enumeration."""
    statics = domain.static_predicates
    by_type = _objects_by_type(domain, objects)
    static_facts = {a for a in init if a.predicate in statics}
    # every type-consistent binding once, with the facts it needs (the static conditions, which
    # rule out most bindings, bound and tested first, each as soon as it is bound)
    candidates: list[tuple[Action, frozenset[Atom]]] = []
    for op in domain.operators:
        types = op.param_types or [None] * len(op.params)
        conds = sorted(op.preconditions, key=lambda pc: pc.atom.predicate not in statics)
        for args in itertools.product(*(by_type.get(t, []) for t in types)):
            b = dict(zip(op.params, args, strict=True))
            needs: set[Atom] = set()
            for pc in conds:
                p = pc.atom.bind(b)
                if p.value is True and p.predicate in statics and p not in static_facts:
                    break
                if p.value is False and p.predicate in statics and Atom(p.predicate, p.args, True) in static_facts:
                    break
                if p.value is True and p.predicate not in statics and pc.criticality > level:
                    needs.add(p)
            else:
                candidates.append((Action(op, args), frozenset(needs)))
    reached = set(init)
    found: set[tuple[str, tuple[str, ...]]] = set()
    changed = True
    while changed:  # each round adds an action or stops: bounded by the finite bindings
        changed = False
        for act, needs in candidates:
            if act.key not in found and needs <= reached:
                found.add(act.key)
                changed = True
                reached |= {e for e in act.effects() if e.value is True}
    return found


@pytest.mark.parametrize("name", DOMAINS)
def test_the_join_finds_exactly_the_type_consistent_reachable_bindings(name: str) -> None:
    prob = load_pddl(CLASSICAL / name / "domain.pddl", CLASSICAL / name / "p02.pddl", mutexes=False)
    task_grounding.clear_cache()
    g = grounding(prob.domain, prob.objects, prob.init, -1)
    got = {(a.operator.name, tuple(a.args)) for a in g.actions}
    init = {a for a in prob.init.atoms() if a.value is True}
    assert got == brute_force(prob.domain, prob.objects, init, -1)
    assert got  # every instance has applicable actions: an empty grounding would pass trivially


CHAIN_DOMAIN = """(define (domain chain)
  (:requirements :strips :typing)
  (:types node)
  (:predicates (edge ?a ?b - node) (reached ?a - node) (pair ?a ?b - node) (linked ?a ?b - node))
  (:action step :parameters (?a ?b - node)
    :precondition (and (reached ?a) (edge ?a ?b)) :effect (reached ?b))
  (:action join :parameters (?a ?b - node)
    :precondition (and (reached ?a) (reached ?b) (pair ?a ?b)) :effect (linked ?a ?b))
  (:action close :parameters (?a ?b ?c - node)
    :precondition (and (linked ?a ?b) (linked ?b ?c) (reached ?c)) :effect (linked ?a ?c)))
"""


def test_a_fixpoint_of_many_rounds_finds_bindings_whose_facts_are_new_together(tmp_path: Path) -> None:
    """After the first round only the bindings that use a new fact are joined (semi-naive,
    planning/joins.py): a chain reached one node per round, ``join`` needing two facts that become
    true in the same round, and ``close`` joining two facts of one predicate, must still give the
    brute-force fixpoint's bindings."""
    n = 7
    nodes = " ".join(f"n{i}" for i in range(n))
    edges = " ".join(f"(edge n{i} n{i + 1})" for i in range(n - 1))
    pairs = " ".join(f"(pair n{i} n{j})" for i in range(n) for j in range(n) if (i + j) % 3 == 0)
    (tmp_path / "d.pddl").write_text(CHAIN_DOMAIN)
    (tmp_path / "p.pddl").write_text(f"""(define (problem c) (:domain chain) (:objects {nodes} - node)
      (:init (reached n0) {edges} {pairs}) (:goal (linked n0 n{n - 1})))""")
    prob = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl", mutexes=False)
    task_grounding.clear_cache()
    g = grounding(prob.domain, prob.objects, prob.init, -1)
    got = {(a.operator.name, tuple(a.args)) for a in g.actions}
    init = {a for a in prob.init.atoms() if a.value is True}
    want = brute_force(prob.domain, prob.objects, init, -1)
    assert got == want
    assert {a for a, _ in got} == {"step", "join", "close"}  # every operator fires, in rounds after the first
