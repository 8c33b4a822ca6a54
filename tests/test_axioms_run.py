"""``nowplan run`` on domains with derived predicates evaluated by rules (issue 18).

The world and the belief recompute the derived atoms after every action
(planning/derived_state.DerivedClosure); planner calls search forward at every
level; the automatic hierarchy places a derived predicate at the level of
what its rules read.  Every executed run is replayed by the independent
checker tests/pddl_sim.py on the original files.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.acting.strategy import parse_strategy
from nowplan.cli import main
from nowplan.commands.run import axiom_strategy
from nowplan.core.atoms import Atom
from nowplan.errors import UsageError
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.abstraction import derive_hierarchy, literal_levels, violations
from nowplan.planning.config import PlannerConfig
from nowplan.planning.derived_state import DerivedClosure, derived_cones
from nowplan.worlds.symbolic import SymbolicWorld

from pddl_sim import check_plan

DATA = Path(__file__).resolve().parent / "data"
AX, RUN = DATA / "pddl_axioms", DATA / "pddl_axioms_run"


def derived_true(state: object, domain: object) -> set[str]:
    return {str(a) for a in state.atoms() if a.predicate in domain.derived}  # type: ignore[attr-defined]


def test_the_closure_recomputes_derived_atoms_from_the_basic_facts() -> None:
    prob = load_pddl(AX / "doors-domain.pddl", AX / "doors-p01.pddl")
    dom = prob.domain
    close = DerivedClosure(dom, prob.objects)
    s0 = close(prob.init)
    assert derived_true(s0, dom) == {"walkable(r1)"}
    assert close(s0) is s0  # nothing to change
    act = next(a for a in _actions(prob) if a.pddl() == "(pick-up k1 r1)")
    opened = next(a for a in _actions(prob) if a.pddl() == "(open-door k1 r1 r2)")
    world = SymbolicWorld(dom, prob.init, closure=close)
    assert derived_true(world.state, dom) == {"walkable(r1)"}
    world.apply(act)
    assert world.applicable(opened)  # its precondition walkable(r1) is derived
    world.apply(opened)
    assert derived_true(world.state, dom) == {"walkable(r1)", "walkable(r2)"}
    # a stale derived atom is dropped, whatever the state said
    stale = world.state.apply([Atom("walkable", ("r5",), True)])
    assert derived_true(close(stale), dom) == {"walkable(r1)", "walkable(r2)"}


def _actions(prob: object) -> list:  # type: ignore[type-arg]
    from nowplan.planning.task_grounding import grounding

    return list(grounding(prob.domain, prob.objects, prob.init, -(10**9)).actions)  # type: ignore[attr-defined]


def _run(capsys: pytest.CaptureFixture[str], tmp_path: Path, dom: Path, prob: Path, *extra: str) -> dict:  # type: ignore[type-arg]
    trace = tmp_path / "t.jsonl"
    code = main(["run", str(dom), str(prob), "--json", "--trace", str(trace), *extra])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["outcome"] == "reached", out
    done = [ev["action"] for ev in map(json.loads, trace.read_text().splitlines())
            if ev.get("event") == "observation" and ev.get("success") and ev["action"]]
    assert len(done) == out["actions"]
    check_plan(dom.read_text(), prob.read_text(), done)  # the executed actions reach the goal
    return out  # type: ignore[no-any-return]


@pytest.mark.parametrize("strategy", ["flat", "hpn"])
@pytest.mark.parametrize("name", [
    (AX, "doors", "p01"),  # the goal is derived (walkable through the opened doors)
    (AX, "grid", "p01"),  # preconditions are derived (not tripping), recursion (powered)
    (RUN, "blocks-above", "p01"),  # recursion (above) in the goal, clear derived in preconditions
    (RUN, "courier", "p01"),  # a derived goal (delivered) and a recursive precondition (reach)
])
def test_run_reaches_and_the_executed_actions_are_valid(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                        name: tuple[Path, str, str], strategy: str) -> None:
    d, dom, p = name
    _run(capsys, tmp_path, d / f"{dom}-domain.pddl", d / f"{dom}-{p}.pddl", "--strategy", strategy)


@pytest.mark.parametrize("crit", ["auto", str(RUN / "courier.crit")])
def test_hierarchical_runs_with_derived_predicates(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                                                   crit: str) -> None:
    out = _run(capsys, tmp_path, RUN / "courier-domain.pddl", RUN / "courier-p01.pddl", "--criticality", crit)
    # abstract steps were refined (the hierarchy was used), and no plan was given up for a derived goal
    # the pre-images lost (derived literals no action can change are kept: DerivedCones)
    assert out["plans_made"] > 1 and out["replans"] == 0


def test_the_hierarchy_places_derived_predicates_at_the_level_of_what_they_read() -> None:
    dom = load_pddl(RUN / "courier-domain.pddl", RUN / "courier-p01.pddl").domain
    h = derive_hierarchy(dom)
    assert h.top == 2 and dict(h.derived) == {"delivered": 2, "reach": 1}
    assert violations(dom, literal_levels(dom, h)) == []
    drive = next(op for op in dom.operators if op.name == "drive")
    reach = next(p.atom for p in drive.preconditions if p.atom.predicate == "reach")
    assert h.criticality(dom, drive, reach) == h.top + 1  # at drive's own level: kept at every level
    # blocksworld's derived clear/above read on and holding: one level, flat
    assert derive_hierarchy(load_pddl(RUN / "blocks-above-domain.pddl", RUN / "blocks-above-p01.pddl").domain).top == 0


def test_cones_tell_which_actions_can_change_a_derived_atom() -> None:
    prob = load_pddl(RUN / "courier-domain.pddl", RUN / "courier-p01.pddl")
    cones = derived_cones(prob.domain)
    p1 = Atom("delivered", ("p1",), True)
    assert cones.touches([Atom("at-p", ("p1", "l5"), True)], p1)
    assert not cones.touches([Atom("at-p", ("p2", "l6"), True), Atom("at-t", ("t1", "l2"), True)], p1)
    reach = Atom("reach", ("t1", "l3"), True)  # recursive: any open road, t1's position
    assert cones.touches([Atom("open", ("l4", "l5"), True)], reach)
    assert cones.touches([Atom("at-t", ("t1", "l2"), False)], reach)
    assert not cones.touches([Atom("at-t", ("t2", "l2"), False)], reach)


def test_a_planner_set_to_regress_is_refused_in_one_line() -> None:
    dom = load_pddl(AX / "doors-domain.pddl", AX / "doors-p01.pddl").domain
    s = parse_strategy("hpn")
    assert axiom_strategy(dom, s).planner.engine == "forward"
    from dataclasses import replace

    with pytest.raises(UsageError, match="recursive derived predicates") as err:
        axiom_strategy(dom, replace(s, planner=PlannerConfig(engine="regression")))
    assert "\n" not in str(err.value)
