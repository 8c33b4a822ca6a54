"""The concrete grounding ``--criticality auto`` makes once, shared with every level of the run.

``prepare_problem`` grounds the problem concretely (reachability statics, dead-end test);
:func:`nowplan.planning.task_grounding.share_concrete` files it as the prepared domain's grounding
at every level, and a call that needs fewer operators gets them filtered from it
(``_restrict``).  Each must be exactly what grounding at that level would find: the same
actions, the same reached atoms, the prepared operators' preconditions.
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.domain import Problem
from nowplan.domains.registry import Episode
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import task_grounding
from nowplan.planning.problem_hierarchy import prepare_problem
from nowplan.planning.task_grounding import Grounding, grounding
from nowplan.worlds.symbolic import SymbolicWorld

CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"
DOMAINS = ["logistics", "zenotravel", "driverlog", "depots", "miconic", "satellite", "gripper", "barman"]


def prepared(name: str, k: int = 1) -> Problem:
    return prepare_problem(load_pddl(CLASSICAL / name / "domain.pddl", CLASSICAL / name / f"p0{k}.pddl", "auto"))


@cache
def prepared_once(name: str) -> Problem:
    return prepared(name, 2)


def fresh(p: Problem, level: int, operators: frozenset[str] | None = None) -> Grounding:
    """What grounding at ``level`` finds from the initial state, without any cache."""
    init = {a for a in p.init.atoms() if a.value is True}
    return task_grounding._ground(p.domain, p.objects, init, p.domain.static_predicates, level, operators)


def same(a: Grounding, b: Grounding) -> None:
    assert {x.key for x in a.actions} == {x.key for x in b.actions}
    assert a.reached == b.reached


@pytest.mark.parametrize("name", DOMAINS)
def test_every_level_is_filed_with_what_it_would_ground(name: str) -> None:
    task_grounding._CACHE.clear()
    p = prepared(name)
    if p.domain.top_level <= 0:
        pytest.skip(f"{name}: one level")
    for level in (-(10**9), *range(-1, p.domain.top_level + 1)):
        shared = grounding(p.domain, p.objects, p.init, level)
        assert shared.shared, level
        same(shared, fresh(p, level))
        for act in shared.actions:
            assert act.operator in p.domain.operators  # the prepared operators, with their statics
            b = act.bindings
            assert act.preconditions() == tuple(pc.atom.bind(b) for pc in act.operator.preconditions)
            assert act.effects() == tuple(e.bind(b) for e in act.operator.effects)


@pytest.mark.parametrize("name", ["logistics", "zenotravel", "miconic", "satellite"])
@pytest.mark.timeout(300, method="thread")  # hypothesis and the signal method: see pyproject.toml
@settings(max_examples=15, deadline=None)
@given(data=st.data())
def test_fewer_operators_are_filtered_as_grounding_them_would_find(name: str, data: st.DataObject) -> None:
    p = prepared_once(name)
    if p.domain.top_level <= 0:
        return
    names = sorted(op.name for op in p.domain.operators)
    ops = frozenset(data.draw(st.lists(st.sampled_from(names), min_size=1, unique=True), label="operators"))
    level = data.draw(st.sampled_from([-(10**9), *range(-1, p.domain.top_level + 1)]), label="level")
    init = {a for a in p.init.atoms() if a.value is True}
    full = fresh(p, level)
    got = task_grounding._restrict(full, ops, init, level, p.domain.static_predicates)
    same(got, fresh(p, level, ops))
    assert got.operators == ops and not got.shared


def test_a_call_needing_fewer_operators_gets_only_those() -> None:
    task_grounding._CACHE.clear()
    p = prepared("miconic")
    top = p.domain.top_level
    ops = frozenset({"board", "depart"})
    g = grounding(p.domain, p.objects, p.init, top, ops)
    assert {a.operator.name for a in g.actions} <= ops
    same(g, fresh(p, top, ops))


def _groundings_of_a_run(p: Problem, name: str, monkeypatch: pytest.MonkeyPatch) -> tuple[Any, list[int]]:
    """An HPN run (forward search, refine-flat) of ``p``, and one entry per grounding it made."""
    from dataclasses import replace

    calls: list[int] = []
    real = task_grounding._ground

    def counted(*args: object, **kw: object) -> Grounding:
        calls.append(1)
        return real(*args, **kw)  # type: ignore[arg-type]

    monkeypatch.setattr(task_grounding, "_ground", counted)
    strat = parse_strategy("hpn+refine-flat")
    strat = replace(strat, planner=replace(strat.planner, engine="forward"))
    m = run_episode(Episode(p, SymbolicWorld(p.domain, p.init, seed=0), SymbolicBelief(p.init), name), strat)
    return m, calls


@pytest.mark.parametrize("name", ["logistics", "zenotravel", "driverlog"])
def test_an_auto_run_grounds_the_problem_once(name: str, monkeypatch: pytest.MonkeyPatch) -> None:
    """After prepare_problem, no planner call of an HPN run grounds the problem again."""
    task_grounding._CACHE.clear()
    p = prepared(name)
    m, calls = _groundings_of_a_run(p, name, monkeypatch)
    assert m.outcome.value == "reached"
    assert m.plans_made > 1
    assert calls == []


def test_a_dropped_condition_without_a_static_is_not_shared(tmp_path: Path) -> None:
    """A 0-ary precondition that a level drops gets no reachability static: that level may ground
    actions the concrete level does not, so nothing is filed and each level grounds for itself."""
    dom = tmp_path / "d.pddl"
    dom.write_text("""(define (domain sw) (:requirements :strips :typing) (:types item)
  (:predicates (on) (ready ?i - item) (lit ?i - item) (done ?i - item))
  (:action switch :parameters () :precondition (and) :effect (on))
  (:action prime :parameters (?i - item) :precondition (and) :effect (ready ?i))
  (:action light :parameters (?i - item) :precondition (and (on) (ready ?i)) :effect (lit ?i))
  (:action finish :parameters (?i - item) :precondition (lit ?i) :effect (done ?i)))""")
    prob = tmp_path / "p.pddl"
    prob.write_text("""(define (problem sw1) (:domain sw) (:objects a b - item) (:init)
  (:goal (and (done a) (done b))))""")
    task_grounding._CACHE.clear()
    p = prepare_problem(load_pddl(dom, prob, "auto"))
    assert p.domain.top_level > 0 and any(n.startswith("reachable-") for n in p.domain.predicates)
    for level in range(-1, p.domain.top_level + 1):
        g = grounding(p.domain, p.objects, p.init, level)
        assert not g.shared
        same(g, fresh(p, level))


def test_the_dead_end_fallbacks_flat_domain_is_filed_with_the_concrete_grounding(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """nomystery spends fuel for good, so ``prepare_problem`` plans it flat (every precondition at
    criticality 1): that domain's grounding at each level the run uses is the dead-end test's concrete
    one, re-made on the flat operators (IPC trucks p07 grounded twice before: ~0.5 s of a 2 s run),
    and the run grounds nothing after the set-up."""
    task_grounding._CACHE.clear()
    p = prepared("nomystery")
    assert p.domain.top_level == 0
    for level in (-(10**9), -1, 0):
        shared = grounding(p.domain, p.objects, p.init, level)
        assert shared.shared, level
        same(shared, fresh(p, level))
        for act in shared.actions:
            assert act.operator in p.domain.operators
            b = act.bindings
            assert act.preconditions() == tuple(pc.atom.bind(b) for pc in act.operator.preconditions)
            assert act.preconditions(level) == act.preconditions()
    m, calls = _groundings_of_a_run(p, "nomystery", monkeypatch)
    assert m.outcome.value == "reached"
    assert calls == []
