"""What real IPC files showed about ``nowplan run --criticality auto`` (issue 18, target 2;
benchmarks/auto_ipc.py, benchmarks/results/auto_ipc/): each fix with a small domain of its own."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.cli import main

SHUTTLE = """
(define (domain shuttle) (:requirements :strips :typing)
 (:types place vehicle crate)
 (:predicates (at-v ?v - vehicle ?p - place) (at-c ?c - crate ?p - place) (in ?c - crate ?v - vehicle)
              (link ?a ?b - place))
 (:action move :parameters (?v - vehicle ?a ?b - place)
  :precondition (and (at-v ?v ?a) (link ?a ?b)) :effect (and (at-v ?v ?b) (not (at-v ?v ?a))))
 (:action load :parameters (?c - crate ?v - vehicle ?p - place)
  :precondition (and (at-c ?c ?p) (at-v ?v ?p)) :effect (and (in ?c ?v) (not (at-c ?c ?p))))
 (:action unload :parameters (?c - crate ?v - vehicle ?p - place)
  :precondition (and (in ?c ?v) (at-v ?v ?p)) :effect (and (at-c ?c ?p) (not (in ?c ?v)))))
"""

SHUTTLE_P = """
(define (problem shuttle-1) (:domain shuttle)
 (:objects a b c d - place v - vehicle k1 k2 - crate)
 (:init (at-v v a) (at-c k1 b) (at-c k2 c) (link a b) (link b a) (link b c) (link c b) (link c d) (link d c))
 (:goal (and (at-c k1 d) (at-c k2 a))))
"""


def _files(tmp_path: Path, domain: str, problem: str) -> tuple[str, str]:
    d, p = tmp_path / "domain.pddl", tmp_path / "p01.pddl"
    d.write_text(domain)
    p.write_text(problem)
    return str(d), str(p)


def _events(trace: Path, kind: str) -> list[dict[str, object]]:
    return [e for e in (json.loads(line) for line in trace.read_text().splitlines()) if e["event"] == kind]


def test_cli_auto_plans_forward_at_every_level(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The executive's default engine regresses at abstract levels; on IPC elevators p01 that spent the
    run's whole 60 s on the top-level plan (forward search: 0.03 s). ``--criticality auto`` now
    searches forward at every level, as the automatic hierarchy was measured."""
    dom, prob = _files(tmp_path, SHUTTLE, SHUTTLE_P)
    trace = tmp_path / "t.jsonl"
    assert main(["run", dom, prob, "--criticality", "auto", "--json", "--trace", str(trace)]) == 0
    assert json.loads(capsys.readouterr().out)["outcome"] == "reached"
    plans = _events(trace, "plan")
    assert any(p["levels"] > 0 for p in plans)  # type: ignore[operator]  # the hierarchy is used
    methods = {str(p["method"]) for p in plans}
    assert all(m.startswith("forward") or m == "direct" for m in methods), methods


CORRIDOR = """
(define (domain corridor) (:requirements :strips)
 (:predicates (at ?x) (link ?x ?y))
 (:action move :parameters (?x ?y) :precondition (and (at ?x) (link ?x ?y))
  :effect (and (at ?y) (not (at ?x)))))
"""


def _corridor(n: int) -> str:
    cells = [f"c{i:02d}" for i in range(n)]
    links = " ".join(f"(link {a} {b}) (link {b} {a})" for a, b in zip(cells, cells[1:]))
    return (f"(define (problem corridor-{n}) (:domain corridor) (:objects {' '.join(cells)})\n"
            f" (:init (at c00) {links}) (:goal (at {cells[-1]})))")


def test_cli_run_gives_the_roots_forward_search_the_flat_planners_node_budget(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """The executive's planner calls had the regression search's 50,000 expansions, forward ones too:
    on IPC floor-tile p03/p04, mystery and the one-level domains auto-HPN failed with 'expanded 50000
    states' where ``nowplan plan`` (20,000,000, ended by its time limit) solved.  Here the regression
    budget is cut to 5 so that a 30-cell corridor needs more than it."""
    import nowplan.commands.run as run_cmd
    from dataclasses import replace as dc_replace

    real = run_cmd.parse_strategy

    def small(*a: object, **k: object) -> object:
        s = real(*a, **k)  # type: ignore[arg-type]
        return dc_replace(s, planner=dc_replace(s.planner, max_nodes=5, shortcut_nodes=5))

    monkeypatch.setattr(run_cmd, "parse_strategy", small)
    dom, prob = _files(tmp_path, CORRIDOR, _corridor(30))
    for crit in ([], ["--criticality", "auto"]):
        assert main(["run", dom, prob, *crit, "--json"]) == 0
        doc = json.loads(capsys.readouterr().out)
        assert doc["outcome"] == "reached", doc["reason"]
        assert doc["actions"] == 29
    # an explicit --max-nodes is every call's budget, forward searches' too
    assert main(["run", dom, prob, "--json", "--max-nodes", "5"]) != 0
    assert "expanded 5 states" in json.loads(capsys.readouterr().out)["reason"]


def test_refinements_keep_the_regression_budget_and_the_root_abstract_plan_half_the_time(tmp_path: Path) -> None:
    from types import SimpleNamespace

    from nowplan.acting.refine_flat import ROOT_ABSTRACT_SHARE, call_config, root_time_share
    from nowplan.core.levels import LevelMap, flat_levels
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.config import PlannerConfig

    cfg = PlannerConfig(max_nodes=50_000, forward_max_nodes=20_000_000)
    assert call_config(cfg, True).forward_max_nodes == 20_000_000  # the whole goal's plan
    assert call_config(cfg, False).forward_max_nodes == 50_000  # a refinement
    assert call_config(PlannerConfig(max_nodes=7), False).forward_max_nodes is None
    prob = load_pddl(*_files(tmp_path, SHUTTLE, SHUTTLE_P), "auto")
    ex = SimpleNamespace(strategy=SimpleNamespace(refine_flat=True), _flat_steps=set(), domain=prob.domain)
    root, key = SimpleNamespace(root=True), ("root", 1)
    top = LevelMap(prob.domain.top_level)
    assert prob.domain.top_level > 0
    assert root_time_share(ex, root, key, top) == ROOT_ABSTRACT_SHARE < 1  # type: ignore[arg-type]
    assert root_time_share(ex, root, key, flat_levels()) == 1.0  # type: ignore[arg-type]  # concrete already
    ex._flat_steps.add(key)  # refine-flat plans it concretely now: the rest of the time is its
    assert root_time_share(ex, root, key, top) == 1.0  # type: ignore[arg-type]
    assert root_time_share(ex, SimpleNamespace(root=False), key, top) == 1.0  # type: ignore[arg-type]
