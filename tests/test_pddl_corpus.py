"""IPC-style PDDL files (tests/data/pddl_ipc_style): each plans end to end with ``nowplan plan``.

Every plan replays to the goal on the ORIGINAL files' semantics with the
independent checker of tests/pddl_sim.py (ADL: quantifiers, disjunctions,
conditional effects), with the cost it reports; with unified-planning
installed, its validator (its own PDDL reader) agrees where it reads the
file, and with Fast Downward installed it solves the same problems too.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.cli import main
from nowplan.io.pddl_read import load_pddl

from pddl_sim import check_plan

CORPUS = Path(__file__).resolve().parent / "data" / "pddl_ipc_style"
NAMES = sorted(p.name[: -len("-domain.pddl")] for p in CORPUS.glob("*-domain.pddl"))


def files(name: str) -> tuple[Path, Path]:
    return CORPUS / f"{name}-domain.pddl", CORPUS / f"{name}-p01.pddl"


def test_corpus_is_there() -> None:
    assert {"blocks", "miconic", "transport", "floortile", "zenotravel", "tidybot", "briefcase",
            "rooms"} <= set(NAMES)


@pytest.mark.parametrize("name", NAMES)
def test_plans_end_to_end_and_replays_on_the_original(capsys: pytest.CaptureFixture[str], name: str) -> None:
    dom, prob = files(name)
    code = main(["plan", str(dom), str(prob), "--json", "--time-limit", "20"])
    out = capsys.readouterr()
    assert code == 0, out.out + out.err
    doc = json.loads(out.out)
    assert doc["status"] == "solved" and doc["plan"]
    cost = check_plan(dom.read_text(), prob.read_text(), doc["plan"])
    uses_costs = "total-cost" in dom.read_text().lower()
    assert doc["cost"] == pytest.approx(cost if uses_costs else len(doc["plan"]))


@pytest.mark.parametrize("name", NAMES)
def test_unified_planning_validates(capsys: pytest.CaptureFixture[str], name: str) -> None:
    validate = pytest.importorskip("nowplan.planning.validate")
    pytest.importorskip("unified_planning")
    dom, prob = files(name)
    assert main(["plan", str(dom), str(prob)]) == 0
    steps = capsys.readouterr().out.splitlines()
    try:
        ok, msg = validate.validate_plan(dom, prob, steps)
    except Exception as exc:  # UP's reader refuses some lenient inputs (e.g. undeclared requirements)
        pytest.skip(f"unified-planning does not read {name}: {str(exc)[:120]}")
    assert ok, msg


@pytest.mark.parametrize("name", NAMES)
def test_fast_downward_solves_the_same(name: str) -> None:
    pytest.importorskip("unified_planning")
    pytest.importorskip("up_fast_downward")
    from nowplan.planning.fd import solve_fd

    dom, prob = files(name)
    problem = load_pddl(dom, prob)
    result = solve_fd(problem, time_limit=30)
    assert result.solved and result.plan is not None, result.reason
    steps = [s for s in (a.pddl() for a in result.plan.actions) if s]
    check_plan(dom.read_text(), prob.read_text(), steps)


def test_transport_costs_come_from_road_length() -> None:
    dom, prob = files("transport")
    problem = load_pddl(dom, prob)
    drive = problem.domain.operator_map["drive"]
    from nowplan.core.atoms import Var

    b = {Var("v"): "truck-1", Var("l1"): "city-loc-1", Var("l2"): "city-loc-3"}
    assert drive.instantiate(b).cost() == 10.0
    assert problem.domain.operator_map["pick-up"].cost == 1.0


@pytest.mark.parametrize("name", NAMES)
def test_fast_downward_solves_the_original_files(name: str) -> None:
    """FD on the original text (through unified-planning's reader, ADL included), where that reader accepts it."""
    pytest.importorskip("up_fast_downward")
    shortcuts = pytest.importorskip("unified_planning.shortcuts")
    from unified_planning.io import PDDLReader

    env = shortcuts.get_environment()
    env.credits_stream = None
    env.error_used_name = False
    dom, prob = files(name)
    try:
        problem = PDDLReader().parse_problem(str(dom), str(prob))
    except Exception as exc:  # UP's reader is stricter than ours on some of these files
        pytest.skip(f"unified-planning does not read {name}: {str(exc)[:120]}")
    with shortcuts.OneshotPlanner(name="fast-downward") as planner:
        res = planner.solve(problem, timeout=30)
    assert res.status.name.startswith("SOLVED"), res.status.name
    assert main(["plan", str(dom), str(prob), "--time-limit", "20"]) == 0
