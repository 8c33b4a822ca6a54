"""Resources derived from the operators of a domain that declares none (acting/derived_resources.py)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.acting.derived_resources import derive_resources, movable_fluents, stops_clash
from nowplan.acting.resources import DEFAULT_MODEL, ResourceModel, resource_model
from nowplan.cli import main
from nowplan.core.atoms import Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.operators import Action, Operator, Precondition, Resource, ResourceUse
from nowplan.io.pddl_read import load_pddl

SH, CT, CN = ResourceUse.SHAREABLE, ResourceUse.CONTAINED, ResourceUse.CONTINUAL
DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"


def _uses(domain: Domain, name: str, *args: str) -> dict[tuple[object, ...], ResourceUse]:
    op = next(o for o in domain.operators if o.name == name)
    act = Action(op, args)
    return {r.name: r.use for r in resource_model(domain).uses(act)}


def test_gripper_robot_is_a_shared_holder_and_a_gripper_is_held_by_pick_until_drop() -> None:
    d = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl").domain
    assert ("at-robby", 0) in movable_fluents(d)
    assert ("at", 1) not in movable_fluents(d)  # no operator moves a ball from room to room
    robot = ("holder", "at-robby", 0)
    assert _uses(d, "move", "rooma", "roomb") == {robot: SH, ("stop", "at-robby", 0, "roomb"): SH}
    pick = _uses(d, "pick", "ball1", "rooma", "left")
    assert pick[robot] is SH and pick[("stop", "at-robby", 0, "rooma")] is SH
    assert pick[("held", "free", "left")] is CN  # taken, and taken while the ball is carried
    drop = _uses(d, "drop", "ball1", "roomb", "left")
    assert drop[("held", "free", "left")] is CT  # given back
    assert drop[("stop", "at-robby", 0, "roomb")] is SH


def test_logistics_truck_is_needed_at_the_package_place_and_moved_to_its_destination() -> None:
    d = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p01.pddl").domain
    ops = {o.name: o for o in d.operators}
    load = next(n for n in ops if "load" in n and "truck" in n and not n.startswith("un"))
    drive = next(n for n in ops if "drive" in n)
    dr = ops[drive]
    tr, frm, to = dr.params[0].name, dr.params[1].name, dr.params[2].name
    uses = _uses(d, drive, *(p.name.upper() for p in dr.params))
    holders = [r for r in uses if r[0] == "holder"]
    assert holders and all(uses[h] is SH for h in holders)
    stops = [r for r in uses if r[0] == "stop"]
    # the stop is the destination (the effect), not the place it leaves
    assert any(r[-1] == to.upper() for r in stops) and not any(r[-1] == frm.upper() for r in stops), (tr, uses)
    lo = ops[load]
    lu = _uses(d, load, *(p.name.upper() for p in lo.params))
    assert any(r[0] == "stop" for r in lu) and all(u is SH for r, u in lu.items() if r[0] in ("holder", "stop"))


V, A, B = Var("v"), Var("a"), Var("b")


def _valued_domain(**kw: object) -> Domain:
    preds = {"at": Predicate("at", 1, boolean=False), "road": Predicate("road", 2)}
    drive = Operator("drive", (V, A, B), (Precondition(atom("road", A, B), 1), Precondition(atom("at", V, value=A), 1)),
                     (atom("at", V, value=B),), **kw)  # type: ignore[arg-type]
    return Domain("valued", preds, (drive,))


def test_a_valued_fluent_that_an_operator_changes_is_a_holder_with_its_value_as_the_place() -> None:
    d = _valued_domain()
    assert movable_fluents(d) == {("at", None)}
    res = dict((r.name, r.use) for r in derive_resources(d)["drive"])
    assert res == {("holder", "at", "=", V): SH, ("stop", "at", "=", V, B): SH}


def test_declared_resources_or_model_are_kept_and_nothing_is_derived() -> None:
    own = _valued_domain(resources=(Resource(("truck", V), CT),))
    assert resource_model(own) is DEFAULT_MODEL and resource_model(own).derived is None
    model = ResourceModel()
    silent = Domain("valued", _valued_domain().predicates, _valued_domain().operators, resources=model)
    assert resource_model(silent) is model
    derived = _valued_domain()
    assert resource_model(derived).derived is not None
    assert resource_model(derived) is resource_model(derived)  # kept per domain


def test_two_stops_of_one_holder_clash_only_at_different_places() -> None:
    assert stops_clash(("stop", "at", 1, "t1", "l1"), ("stop", "at", 1, "t1", "l2"))
    assert not stops_clash(("stop", "at", 1, "t1", "l1"), ("stop", "at", 1, "t1", "l1"))
    assert not stops_clash(("stop", "at", 1, "t1", "l1"), ("stop", "at", 1, "t2", "l2"))
    assert not stops_clash(("holder", "at", 1, "t1"), ("holder", "at", 1, "t2"))


def _run(capsys: pytest.CaptureFixture[str], dom: str, prob: str, strategy: str) -> dict[str, object]:
    code = main(["run", str(DATA / dom / "domain.pddl"), str(DATA / dom / prob), "--criticality", "auto",
                 "--strategy", strategy, "--json"])
    out: dict[str, object] = json.loads(capsys.readouterr().out)
    assert code == 0, out
    return out


def test_rchpn_on_pddl_gripper_carries_two_balls_a_trip(capsys: pytest.CaptureFixture[str]) -> None:
    """Auto-HPN's top level in the planner's order moves one ball at a time (p03, 6 balls: 21
    actions, a round trip per ball); with the derived resources the peephole combines drops that
    share the robot's stop, and the run takes both grippers each trip: 17 actions, the flat plan's
    length.  (Regrouping the top-level plan, on by default, does the same: ``noregroup`` shows the
    peephole's own doing; test_regroup.py.)"""
    hpn = _run(capsys, "gripper", "p03.pddl", "hpn+noregroup")
    rchpn = _run(capsys, "gripper", "p03.pddl", "hpn+peephole+noregroup")
    assert hpn["goal_in_world"] and rchpn["goal_in_world"]
    assert isinstance(hpn["execution_cost"], float) and isinstance(rchpn["execution_cost"], float)
    assert rchpn["execution_cost"] < hpn["execution_cost"]
    moves = rchpn["action_counts"]["move"]  # type: ignore[index]
    assert moves <= 5, rchpn  # three trips there, two back


def test_rchpn_on_pddl_logistics_is_never_dearer_than_hpn(capsys: pytest.CaptureFixture[str]) -> None:
    for prob in ("p01.pddl", "p02.pddl"):
        hpn = _run(capsys, "logistics", prob, "hpn")
        rchpn = _run(capsys, "logistics", prob, "hpn+peephole")
        assert rchpn["goal_in_world"]
        assert rchpn["execution_cost"] <= hpn["execution_cost"]  # type: ignore[operator]


def test_a_step_whose_hidden_preconditions_exclude_each_other_is_not_reachable_not_an_error(
        capsys: pytest.CaptureFixture[str]) -> None:
    """Barman's abstract steps hide preconditions that cannot hold together (a hand holding a shot
    and empty); the estimator's small plan for them refused the run with 'goal is contradictory'."""
    dom = Path(__file__).resolve().parents[1] / "benchmarks" / "classical" / "barman"
    code = main(["run", str(dom / "domain.pddl"), str(dom / "p01.pddl"), "--criticality", "auto",
                 "--strategy", "hpn+peephole", "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["goal_in_world"], out
