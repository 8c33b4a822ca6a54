"""Recursive derived predicates (PDDL axioms): stratification, evaluation, planning, refusals.

The files in tests/data/pddl_axioms are written for these tests: ``doors``
(where the agent can walk is the transitive closure of the open doors, except
into rooms that water reaches through open doors: two recursive predicates, one
negated in the other's definition) and ``grid`` (a power network in the spirit
of IPC-2004's PSR: power flows through closed switches; a powered faulty node
trips the network).  Every plan replays to the goal with the independent checker
of tests/pddl_sim.py, which evaluates derived predicates its own (naive) way.
"""

from __future__ import annotations

import functools
import json
import random
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from nowplan.cli import main
from nowplan.core.levels import flat_levels
from nowplan.errors import ModelError
from nowplan.io.pddl_read import load_pddl
from nowplan.io.pddl_syntax import parse_domain
from nowplan.io.pddl_axioms import stratify
from nowplan.io.pddl_write import domain_text, problem_text
from nowplan.planning.axioms import AxiomEvaluator, relaxed_task
from nowplan.planning.forward import search
from nowplan.planning.native import kernel_class
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.task import Task, build_task

from pddl_sim import check_plan

DATA = Path(__file__).resolve().parent / "data" / "pddl_axioms"
INSTANCES = ["doors-p01", "doors-p02", "grid-p01", "grid-p02"]


def files(name: str) -> tuple[Path, Path]:
    return DATA / f"{name.split('-')[0]}-domain.pddl", DATA / f"{name}.pddl"


def _plan_json(capsys: pytest.CaptureFixture[str], dom: Path, prob: Path, *extra: str) -> dict:
    code = main(["plan", str(dom), str(prob), "--json", "--time-limit", "20", *extra])
    out = capsys.readouterr()
    assert code == 0, out.out + out.err
    return json.loads(out.out)


@pytest.mark.parametrize("name", INSTANCES)
def test_plans_and_replays_on_the_original(capsys: pytest.CaptureFixture[str], name: str) -> None:
    dom, prob = files(name)
    doc = _plan_json(capsys, dom, prob)
    assert doc["status"] == "solved" and doc["plan"]
    check_plan(dom.read_text(), prob.read_text(), doc["plan"])
    assert doc["cost"] == len(doc["plan"])


@pytest.mark.parametrize("name", INSTANCES)
@pytest.mark.parametrize("search_kind", ["lama", "gbfs", "astar"])
def test_kernel_and_python_give_the_same_plan(monkeypatch: pytest.MonkeyPatch, name: str, search_kind: str) -> None:
    if kernel_class() is None:
        pytest.skip("the compiled kernel is not built")
    dom, prob = files(name)
    problem = load_pddl(dom, prob)
    task = build_task(problem.domain, problem.objects, problem.init, problem.goal, flat_levels(), lambda a: 1.0)
    native = search(task, method=search_kind)  # type: ignore[arg-type]
    monkeypatch.setenv("NOWPLAN_PURE_PYTHON", "1")
    python = search(build_task(problem.domain, problem.objects, problem.init, problem.goal, flat_levels(),
                               lambda a: 1.0), method=search_kind)  # type: ignore[arg-type]
    assert native.actions is not None and python.actions is not None
    assert [a.pddl() for a in native.actions] == [a.pddl() for a in python.actions]
    assert (native.expanded, native.generated) == (python.expanded, python.generated)
    check_plan(dom.read_text(), prob.read_text(), [a.pddl() for a in native.actions])


def test_the_checker_sees_a_derived_precondition_fail() -> None:
    dom, prob = files("grid-p01")
    # n3 is faulty and powered: the network trips, closing a switch is not allowed
    with pytest.raises(AssertionError, match="precondition of"):
        check_plan(dom.read_text(), prob.read_text(), ["(close b2)"])
    with pytest.raises(AssertionError, match="goal"):
        check_plan(dom.read_text(), prob.read_text(), ["(trip b1)"])


def test_optimal_search_matches_breadth_first_search() -> None:
    """h_max with the rules as cost-0 relaxed actions stays admissible: A* finds the shortest plan."""
    for name in INSTANCES:
        dom, prob = files(name)
        problem = load_pddl(dom, prob)
        task = build_task(problem.domain, problem.objects, problem.init, problem.goal, flat_levels(), lambda a: 1.0)
        res = search(task, method="astar", heuristic="max", cost_type="normal", weight=1.0)
        assert res.actions is not None
        assert len(res.actions) == _bfs_length(task), name


def _bfs_length(task: Task) -> int:
    from nowplan.planning.forward import _apply, _Successors

    succ = _Successors(task)
    frontier, seen, depth = [task.init], {task.init}, 0
    while frontier:
        if any(all(g in s for g in task.goal) for s in frontier):
            return depth
        nxt = []
        for s in frontier:
            for a in succ(s):
                t = _apply(task, s, a)
                if t not in seen:
                    seen.add(t)
                    nxt.append(t)
        frontier, depth = nxt, depth + 1
        assert depth < 50
    raise AssertionError("no plan")


def test_strata_and_recursion() -> None:
    d = parse_domain((DATA / "doors-domain.pddl").read_text(), "doors-domain.pddl")
    s = stratify(d)
    assert s.recursive == {"flooded", "walkable"}
    assert s.stratum["walkable"] == s.stratum["flooded"] + 1
    g = stratify(parse_domain((DATA / "grid-domain.pddl").read_text(), "grid-domain.pddl"))
    assert g.recursive == {"powered"} and g.stratum["tripping"] == g.stratum["powered"]


def test_unstratifiable_axioms_are_refused_in_one_line(capsys: pytest.CaptureFixture[str]) -> None:
    code = main(["plan", str(DATA / "doors-bad-domain.pddl"), str(DATA / "doors-p01.pddl")])
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1
    assert "doors-bad-domain.pddl:4" in err and "not stratifiable" in err and "win" in err


def test_regression_refuses_with_the_fix(capsys: pytest.CaptureFixture[str]) -> None:
    """(``nowplan run`` runs such domains: tests/test_axioms_run.py.)"""
    dom, prob = files("doors-p01")
    problem = load_pddl(dom, prob)
    with pytest.raises(ModelError, match="forward engine"):
        plan(problem.domain, problem.objects, problem.init, problem.goal, flat_levels(),
             PlannerConfig(engine="regression"))
    for args in (["plan", str(dom), str(prob), "--engine", "regression"],
                 ["plan", str(dom), str(prob), "--engine", "fd"]):
        assert main(args) == 2
        err = capsys.readouterr().err
        assert "recursive derived predicates" in err and "rules (flooded, walkable)" in err, args
        assert len(err.strip().splitlines()) == 1


def test_written_domain_reads_back_and_plans_alike(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    for name in INSTANCES:
        dom, prob = files(name)
        problem = load_pddl(dom, prob)
        (tmp_path / "d.pddl").write_text(domain_text(problem.domain))
        (tmp_path / "p.pddl").write_text(problem_text(problem))
        again = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl")
        assert len(again.domain.axioms) == len(problem.domain.axioms)
        # the first plan (--improve 0): the written domain may order its operators differently, which
        # the first search's tie-breaking sees alike but the improvement need not
        first = _plan_json(capsys, dom, prob, "--improve", "0")
        second = _plan_json(capsys, tmp_path / "d.pddl", tmp_path / "p.pddl", "--improve", "0")
        assert first["plan"] == second["plan"]


def test_fast_downward_solves_the_originals() -> None:
    """Fast Downward's own driver (it supports axioms) on the original files: a plan our checker accepts."""
    import importlib.util
    import subprocess
    import sys
    import tempfile

    spec = importlib.util.find_spec("up_fast_downward")
    if spec is None or spec.origin is None:
        pytest.skip("up_fast_downward is not installed")
    driver = Path(spec.origin).parent / "downward" / "fast-downward.py"
    for name in INSTANCES:
        dom, prob = files(name)
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([sys.executable, str(driver), "--alias", "lama-first", str(dom), str(prob)],
                           cwd=tmp, capture_output=True, timeout=120, check=False)
            steps = [ln for ln in (Path(tmp) / "sas_plan").read_text().splitlines() if not ln.startswith(";")]
        check_plan(dom.read_text(), prob.read_text(), steps)


# --------------------------------------------------------------------------- the fixpoint, against a naive closure

GRAPH_DOMAIN = """
(define (domain graphs)
  (:requirements :strips :derived-predicates :negative-preconditions)
  (:predicates (edge ?a ?b) (mark ?a) (reach ?a ?b) (cut ?a ?b) (done))
  (:derived (reach ?a ?b) (or (edge ?a ?b) (exists (?c) (and (reach ?a ?c) (edge ?c ?b)))))
  (:derived (cut ?a ?b) (or (and (mark ?b) (not (reach ?a ?b)))
                            (exists (?c) (and (cut ?a ?c) (edge ?c ?b) (not (reach ?b ?a))))))
  (:action flip-on :parameters (?a ?b) :precondition (not (edge ?a ?b)) :effect (edge ?a ?b))
  (:action flip-off :parameters (?a ?b) :precondition (edge ?a ?b) :effect (not (edge ?a ?b)))
  (:action toggle :parameters (?a) :precondition (not (mark ?a)) :effect (mark ?a))
  (:action finish :parameters (?a ?b) :precondition (and (cut ?a ?b) (not (reach ?a ?a))) :effect (done)))
"""


@functools.lru_cache(maxsize=None)
def _graph_task(n: int, tmp: str) -> Task:
    nodes = [f"v{i}" for i in range(n)]
    init = " ".join(f"(edge {a} {b})" for a in nodes for b in nodes) + " " + " ".join(f"(mark {a})" for a in nodes)
    d, p = Path(tmp) / f"g{n}-d.pddl", Path(tmp) / f"g{n}-p.pddl"
    d.write_text(GRAPH_DOMAIN)
    p.write_text(f"(define (problem g{n}) (:domain graphs) (:objects {' '.join(nodes)}) (:init {init}) "
                 "(:goal (done)))")
    problem = load_pddl(d, p)
    return build_task(problem.domain, problem.objects, problem.init, problem.goal, flat_levels(), lambda a: 1.0)


def _naive(n: int, edges: set[tuple[int, int]], marks: set[int]) -> tuple[set, set]:
    reach = set(edges)
    while True:
        more = {(a, c) for a, b in reach for b2, c in edges if b == b2} - reach
        if not more:
            break
        reach |= more
    cut = {(a, b) for a in range(n) for b in marks if (a, b) not in reach}
    while True:
        more = {(a, c) for a, b in cut for b2, c in edges if b == b2 and (c, a) not in reach} - cut
        if not more:
            break
        cut |= more
    return reach, cut


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 6), st.integers(0, 2**31 - 1))
def test_fixpoint_equals_a_naive_closure(tmp_path_factory: pytest.TempPathFactory, n: int, seed: int) -> None:
    task = _graph_task(n, str(tmp_path_factory.getbasetemp()))
    assert task.axioms is not None
    rng = random.Random(seed)
    p_edge = rng.random()
    edges = {(a, b) for a in range(n) for b in range(n) if rng.random() < p_edge}
    marks = {a for a in range(n) if rng.random() < 0.5}
    ids = {(a.predicate, tuple(a.args), a.value): i for i, a in enumerate(task.facts)}
    def fact(pred: str, args: tuple[str, ...], value: bool) -> set[int]:
        i = ids.get((pred, args, value))
        return set() if i is None else {i}

    state: set[int] = set()
    for a in range(n):
        state |= fact("mark", (f"v{a}",), a in marks)
        for b in range(n):
            state |= fact("edge", (f"v{a}", f"v{b}"), (a, b) in edges)
    # derived facts in the input are ignored (recomputed)
    junk = {i for i, a in enumerate(task.facts) if a.predicate in ("reach", "cut")}
    closed = AxiomEvaluator(task.axioms).evaluate(state | set(rng.sample(sorted(junk), min(3, len(junk)))))
    reach, cut = _naive(n, edges, marks)

    def derived(pred: str, facts: frozenset[int] | set[int]) -> set[tuple[int, int]]:
        return {(int(task.facts[f].args[0][1:]), int(task.facts[f].args[1][1:])) for f in facts
                if task.facts[f].predicate == pred and task.facts[f].value is True}

    assert derived("reach", closed) == reach
    assert derived("cut", closed) == cut
    for a in range(n):
        for b in range(n):
            nr = ("reach", (f"v{a}", f"v{b}"), False)
            if nr in ids:  # "not reach" is a fact: it holds exactly when reach does not
                assert (ids[nr] in closed) == ((a, b) not in reach)
    cls = kernel_class()
    if cls is not None:
        from nowplan.planning.axioms import kernel_axioms

        r = relaxed_task(task)
        nactions, axioms = kernel_axioms(task)
        k = cls(len(task.facts), r.pre, r.add, r.dele, [0.0] * len(r.pre), task.goal,
                [r.by_pre.get(f, ()) for f in range(len(task.facts))], r.no_pre, "ff", nactions=nactions,
                axioms=axioms)
        assert frozenset(k.close(state)) == closed


# --------------------------------------------------------------------------- heuristics stay sound

LOCKS_DOMAIN = """
(define (domain locks)
  (:requirements :strips :derived-predicates :negative-preconditions)
  (:predicates (door ?a ?b) (open ?a ?b) (start ?a) (reach ?a) (alarm ?a) (quiet))
  (:derived (reach ?a) (or (start ?a) (exists (?b) (and (reach ?b) (open ?b ?a)))))
  (:derived (quiet) (not (exists (?a) (and (alarm ?a) (reach ?a)))))
  (:action unlock :parameters (?a ?b) :precondition (and (door ?a ?b) (reach ?a) (not (open ?a ?b)))
    :effect (open ?a ?b))
  (:action lock :parameters (?a ?b) :precondition (and (open ?a ?b) (reach ?a)) :effect (not (open ?a ?b))))
"""


@settings(max_examples=25, deadline=None)
@given(st.integers(3, 6), st.integers(0, 2**31 - 1))
def test_optimal_search_with_axioms_matches_bfs_on_random_graphs(tmp_path_factory: pytest.TempPathFactory,
                                                                  n: int, seed: int) -> None:
    """A* with h_max (rules as cost-0 relaxed actions, negated derived facts free) finds shortest plans."""
    rng = random.Random(seed)
    # a corridor v0 .. v(n-1) of locked doors, random shortcuts, and alarm rooms a0, a1 hanging off
    # corridor rooms by doors, some open: the goal (reach the end, no alarm room reachable) needs
    # locking those again, an alarm reachable through a negated derived condition
    doors = [(i, i + 1) for i in range(n - 1)] + [(a, b) for a in range(n) for b in range(a + 2, n)
                                                  if rng.random() < 0.2]
    opened = [d for d in doors if rng.random() < 0.25]
    hang = [(rng.randrange(n - 1), k) for k in range(2)]
    open_alarm = [h for h in hang if rng.random() < 0.6]
    init = " ".join([f"(door v{a} v{b})" for a, b in doors] + [f"(open v{a} v{b})" for a, b in opened]
                    + [f"(door v{c} a{k})" for c, k in hang] + [f"(open v{c} a{k})" for c, k in open_alarm]
                    + ["(alarm a0)", "(alarm a1)", "(start v0)"])
    tmp = tmp_path_factory.mktemp("locks")
    (tmp / "d.pddl").write_text(LOCKS_DOMAIN)
    (tmp / "p.pddl").write_text(f"(define (problem r) (:domain locks) (:objects a0 a1 {' '.join(f'v{i}' for i in range(n))}) "
                                f"(:init {init}) (:goal (and (reach v{n - 1}) (quiet))))")
    problem = load_pddl(tmp / "d.pddl", tmp / "p.pddl")
    task = build_task(problem.domain, problem.objects, problem.init, problem.goal, flat_levels(), lambda a: 1.0)
    shortest: int | None = None
    if not task.unsolvable:  # (a goal atom unreachable even in the relaxation: no plan)
        try:
            shortest = _bfs_length(task)
        except AssertionError:
            shortest = None
    res = search(task, method="astar", heuristic="max", cost_type="normal", weight=1.0)
    if shortest is None:
        assert res.actions is None
        return
    assert res.actions is not None and len(res.actions) == shortest
    steps = [a.pddl() for a in res.actions]
    check_plan((tmp / "d.pddl").read_text(), (tmp / "p.pddl").read_text(), steps)
