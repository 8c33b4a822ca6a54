"""``nowplan plan``: every classic problem solved and validated, JSON output, exit codes, errors."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.cli import main

from test_pddl_read import DATA
from test_pddl_write import CASES

LOG = DATA / "logistics"


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(["plan", *argv])
    out = capsys.readouterr()
    return code, out.out, out.err


@pytest.mark.parametrize(("domain", "problem"), CASES)
def test_every_classic_problem_is_solved_and_valid(
    capsys: pytest.CaptureFixture[str], domain: str, problem: str
) -> None:
    dpath, ppath = DATA / domain / "domain.pddl", DATA / domain / problem
    code, out, err = run(capsys, str(dpath), str(ppath), "--time-limit", "20")
    assert code == 0, out + err
    lines = out.splitlines()
    assert lines and all(line.startswith("(") and line.endswith(")") for line in lines)
    validate = pytest.importorskip("nowplan.planning.validate")
    ok, msg = validate.validate_plan(dpath, ppath, lines)
    assert ok, msg


def test_json_document(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, str(LOG / "domain.pddl"), str(LOG / "p01.pddl"), "--json", "--seed", "3")
    doc = json.loads(out)
    assert code == 0
    assert doc["status"] == "solved" and doc["cost"] == len(doc["plan"]) > 0
    assert doc["method"] == "forward:lama" and doc["engine"] == "nowplan" and doc["level"] == "flat"
    assert doc["planning_time_s"] >= 0


def test_criticality_file_still_gives_a_concrete_plan(capsys: pytest.CaptureFixture[str]) -> None:
    args = [str(LOG / "domain.pddl"), str(LOG / "p01.pddl"), "--criticality", str(LOG / "logistics.crit")]
    code, flat, _ = run(capsys, *args)
    assert code == 0 and ("(drive-truck" in flat or "(fly-airplane" in flat)
    code, top, _ = run(capsys, *args, "--level", "top")
    assert code == 0 and "drive-truck" not in top and "fly-airplane" not in top
    code, _, err = run(capsys, *args, "--level", "5")
    assert code == 2 and "--level 5 is out of range" in err


def test_a_heuristic_for_gbfs_is_refused_with_lama(capsys: pytest.CaptureFixture[str]) -> None:
    args = [str(LOG / "domain.pddl"), str(LOG / "p01.pddl")]
    code, out, err = run(capsys, *args, "--heuristic", "add")
    assert code == 2 and out == "" and "--search gbfs or astar" in err and err.count("\n") == 1
    code, out, _ = run(capsys, *args, "--heuristic", "add", "--search", "gbfs", "--json")
    assert code == 0 and json.loads(out)["method"] == "forward:gbfs"


def test_fd_engine(capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("up_fast_downward")
    code, out, _ = run(capsys, str(LOG / "domain.pddl"), str(LOG / "p02.pddl"), "--engine", "fd", "--json")
    doc = json.loads(out)
    assert code == 0 and doc["status"] == "solved" and doc["method"] == "fd:fast-downward"


def unsolvable(tmp_path: Path) -> Path:
    bw = DATA / "blocksworld"
    p = tmp_path / "p.pddl"
    p.write_text((bw / "p01.pddl").read_text().replace("(on a b) (on b c)", "(on a b) (on b a)"))
    return p


def test_unsolvable_exits_1(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    dom = str(DATA / "blocksworld" / "domain.pddl")
    code, out, _ = run(capsys, dom, str(unsolvable(tmp_path)))
    assert code == 1 and out.startswith("unsolvable")
    code, out, _ = run(capsys, dom, str(unsolvable(tmp_path)), "--json")
    assert code == 1 and json.loads(out)["status"] == "unsolvable" and json.loads(out)["plan"] == []


def test_node_limit_exits_1(capsys: pytest.CaptureFixture[str]) -> None:
    bw = DATA / "blocksworld"
    code, out, _ = run(capsys, str(bw / "domain.pddl"), str(bw / "p04.pddl"), "--max-nodes", "2")
    assert code == 1 and out.startswith("node_limit")


def test_missing_file_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    code, out, err = run(capsys, str(tmp_path / "none.pddl"), str(LOG / "p01.pddl"))
    assert code == 2 and out == ""
    assert err == f"nowplan plan: error: {tmp_path / 'none.pddl'}: file not found (check the path)\n"


def test_bad_pddl_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    bad = tmp_path / "d.pddl"
    bad.write_text((LOG / "domain.pddl").read_text().replace("(:action", "(:durative-action", 1))
    code, _, err = run(capsys, str(bad), str(LOG / "p01.pddl"))
    assert code == 2 and err.count("\n") == 1
    assert "durative actions (temporal planning) (:durative-action) are not supported" in err


@pytest.mark.parametrize(
    "argv",
    [["--bogus"], ["--engine", "magic"], ["--time-limit", "-1"], ["--max-nodes", "x"], ["--level", "low"]],
)
def test_bad_options(capsys: pytest.CaptureFixture[str], argv: list[str]) -> None:
    with pytest.raises(SystemExit) as info:
        main(["plan", str(LOG / "domain.pddl"), str(LOG / "p01.pddl"), *argv])
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert "error:" in err and err.count("\n") == 1


def test_out_of_memory_is_one_line(capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch) -> None:
    """A search that outgrows the machine ends with one line naming the bounds, exit 1, no traceback."""
    import nowplan.commands.plan as plan_cmd

    def exhausted(args: object) -> int:
        raise MemoryError

    monkeypatch.setattr(plan_cmd, "run", exhausted)
    code, out, err = run(capsys, str(LOG / "domain.pddl"), str(LOG / "p01.pddl"))
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and "out of memory" in err and "--max-nodes" in err


COST_DOMAIN = """(define (domain detour)
  (:requirements :typing :action-costs)
  (:types place)
  (:predicates (at ?p - place) (road ?a ?b - place) (toll ?a ?b - place))
  (:functions (total-cost))
  (:action drive :parameters (?a ?b - place)
    :precondition (and (at ?a) (road ?a ?b))
    :effect (and (not (at ?a)) (at ?b) (increase (total-cost) 1)))
  (:action fly :parameters (?a ?b - place)
    :precondition (and (at ?a) (toll ?a ?b))
    :effect (and (not (at ?a)) (at ?b) (increase (total-cost) 100))))
"""
COST_PROBLEM = """(define (problem detour-1) (:domain detour)
  (:objects s x y g - place)
  (:init (at s) (road s x) (road x y) (road y g) (toll s g) (= (total-cost) 0))
  (:goal (at g))
  (:metric minimize (total-cost)))
"""


def test_cost_type_decides_what_the_heuristic_prefers(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    # one flight (cost 100) or three drives (cost 3): with unit costs (Fast Downward's lama-first) the relaxed
    # plan is the flight; with cost + 1 (the default) the drives; --improve 0 keeps the first plan
    (tmp_path / "d.pddl").write_text(COST_DOMAIN)
    (tmp_path / "p.pddl").write_text(COST_PROBLEM)
    args = [str(tmp_path / "d.pddl"), str(tmp_path / "p.pddl"), "--json", "--improve", "0"]
    code, out, _ = run(capsys, *args)
    assert code == 0 and json.loads(out)["cost"] == 3
    code, out, _ = run(capsys, *args, "--cost-type", "one")
    doc = json.loads(out)
    assert code == 0 and doc["cost"] == 100 and doc["plan"] == ["(fly s g)"]
    code, out, _ = run(capsys, *args, "--cost-type", "normal")
    assert code == 0 and json.loads(out)["cost"] == 3


CLASSICAL = Path(__file__).resolve().parents[1] / "benchmarks" / "classical"


@pytest.mark.parametrize("domain", ["depots", "nomystery", "blocksworld"])  # (floortile: the UP validator refuses its action name "up")
def test_regression_engine_prunes_h2_pairs_and_plans_validly(capsys: pytest.CaptureFixture[str], domain: str) -> None:
    """`--engine regression` drops subgoals holding pairs no reachable state holds (planning/h2.py): valid
    plans, fewer expansions than `--no-mutexes` (which turns the invariants and h2 off)."""
    dpath, ppath = CLASSICAL / domain / "domain.pddl", CLASSICAL / domain / "p01.pddl"
    base = [str(dpath), str(ppath), "--engine", "regression", "--json", "--time-limit", "60", "--weight", "1"]
    code, out, _ = run(capsys, *base)
    assert code == 0
    on = json.loads(out)
    validate = pytest.importorskip("nowplan.planning.validate")
    ok, msg = validate.validate_plan(dpath, ppath, on["plan"])
    assert ok, msg
    code, out, _ = run(capsys, *base, "--no-mutexes")
    off = json.loads(out)
    assert off["status"] != "solved" or len(off["plan"]) == len(on["plan"])  # (A*: both optimal)
    assert on["expanded"] < off["expanded"]
