"""Constructs of real IPC files that the front end first refused (found by benchmarks/ipc_check.py).

Each test is a small file written here that reproduces the construct of an
IPC domain; every plan replays on the original semantics (tests/pddl_sim.py).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from nowplan.cli import main
from nowplan.io import pddl_adl
from nowplan.io.pddl_ast import EAnd, EForall, ELit, EWhen, FAtom, FNot, TypedName
from nowplan.io.pddl_read import load_pddl, read_domain

from pddl_sim import check_plan


def solve(tmp_path: Path, domain: str, problem: str, capsys: pytest.CaptureFixture[str]) -> list[str]:
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    d.write_text(domain)
    p.write_text(problem)
    code = main(["plan", str(d), str(p), "--time-limit", "20"])
    out = capsys.readouterr()
    assert code == 0, out.out + out.err
    steps = out.out.splitlines()
    check_plan(domain, problem, steps)
    return steps


# IPC-2006 storage declares `area - object` and then `area crate - surface` in one (:types ...).
STORE = """\
(define (domain store)
  (:requirements :typing)
  (:types hoist surface area - object
          spot - area
          area crate - surface)
  (:predicates (on ?c - crate ?s - surface) (at ?h - hoist ?a - area) (clear ?s - surface))
  (:action put
    :parameters (?h - hoist ?c - crate ?from - surface ?to - area)
    :precondition (and (at ?h ?to) (on ?c ?from) (clear ?to))
    :effect (and (on ?c ?to) (not (on ?c ?from)) (not (clear ?to)) (clear ?from))))
"""

STORE_P = """\
(define (problem store-1) (:domain store)
  (:objects h - hoist c - crate s1 s2 - spot)
  (:init (at h s2) (on c s1) (clear s2))
  (:goal (on c s2)))
"""


def test_type_declared_again_takes_the_later_parent(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                    caplog: pytest.LogCaptureFixture) -> None:
    (tmp_path / "d.pddl").write_text(STORE)
    (tmp_path / "p.pddl").write_text(STORE_P)
    prob = load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl")
    assert prob.domain.types["area"] == "surface" and prob.domain.types["spot"] == "area"
    assert not any("declared again" in r.getMessage() for r in caplog.records)  # object -> surface: a refinement
    # a spot is a surface: `put` may take a crate from one
    assert solve(tmp_path, STORE, STORE_P, capsys) == ["(put h c s1 s2)"]


def test_type_declared_again_with_another_parent_warns(tmp_path: Path, caplog: pytest.LogCaptureFixture) -> None:
    dom = STORE.replace("area crate - surface)", "area crate - surface area - surface spot - hoist)")
    (tmp_path / "d.pddl").write_text(dom)
    types = read_domain(tmp_path / "d.pddl").types
    assert types["area"] == "surface" and types["spot"] == "hoist"  # the later parent, as Fast Downward
    assert any("'spot' is declared again" in r.getMessage() for r in caplog.records)


# IPC-2000 schedule: each action clears old values with (forall (?v) (when (p ?x ?v) (not (p ?x ?v))))
# and sets a flag with (when (not (flag)) (flag)): 11 effect conditions in do-roll.
def schedule_like(values: int) -> tuple[str, str]:
    dom = """\
(define (domain paint)
  (:requirements :typing :conditional-effects)
  (:types part colour)
  (:predicates (painted ?x - part ?c - colour) (busy) (done ?x - part))
  (:action paint
    :parameters (?x - part ?c - colour)
    :precondition (not (busy))
    :effect (and (busy) (done ?x)
                 (when (not (busy)) (busy))
                 (forall (?old - colour) (when (painted ?x ?old) (not (painted ?x ?old))))
                 (painted ?x ?c)))
  (:action rest
    :parameters ()
    :precondition (busy)
    :effect (forall (?x - part) (when (done ?x) (not (done ?x)))))
  (:action toggle-busy
    :parameters ()
    :effect (and (not (busy)) (when (not (busy)) (busy)))))
"""
    colours = " ".join(f"c{i}" for i in range(values))
    prob = f"""\
(define (problem paint-1) (:domain paint)
  (:objects a b - part {colours} - colour)
  (:init (painted a c0) (painted a c1) (busy))
  (:goal (and (painted a c2) (not (painted a c0)) (not (painted a c1)) (painted b c0))))
"""
    return dom, prob


def test_self_cancelling_conditions_do_not_count_against_the_bound(tmp_path: Path,
                                                                    capsys: pytest.CaptureFixture[str]) -> None:
    dom, prob = schedule_like(pddl_adl.MAX_CONDITIONS + 4)  # 14 colours: 2**15 variants without the rule
    plan = solve(tmp_path, dom, prob, capsys)
    assert "(paint a c2)" in plan and "(paint b c0)" in plan
    paint = [o for o in load_pddl(tmp_path / "d.pddl", tmp_path / "p.pddl").domain.operators
             if (o.pddl_name or o.name) == "paint"]
    assert len(paint) == 1  # one unconditional operator


def test_toggle_keeps_its_conditional_add(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """(and (not (busy)) (when (not (busy)) (busy))) flips busy: the add must stay conditional."""
    dom, _ = schedule_like(2)
    prob = """\
(define (problem paint-2) (:domain paint)
  (:objects a - part c0 - colour)
  (:init (busy))
  (:goal (painted a c0)))
"""
    # from busy: toggle-busy makes it free (the delete), then paint; the rule must not turn the
    # conditional add into an unconditional one (that would keep busy forever: unsolvable)
    assert solve(tmp_path, dom, prob, capsys) == ["(toggle-busy)", "(paint a c0)"]


def test_flatten_moves_only_self_cancelling_effects() -> None:
    p = FAtom("p", ("?x",), 1)
    q = FAtom("q", ("?x",), 1)
    eff = EAnd((
        EForall((TypedName("?y", (), 1),), EWhen(FAtom("p", ("?y",), 1), ELit(FAtom("p", ("?y",), 1), False), 1), 1),
        EWhen(FNot(q), ELit(q, True), 1),
        EWhen(p, ELit(q, False), 1),
    ))
    flat = pddl_adl.flatten_effects(eff, lambda types: ["a", "b"], lambda lit: None, "test")
    assert ("p", ("a",), False) in flat.base and ("p", ("b",), False) in flat.base
    # q is deleted under another condition: its conditional add stays conditional
    assert ("q", ("?x",), True) not in flat.base
    assert len(flat.conditional) == 2


def test_pddl12_length_section_is_ignored(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                          caplog: pytest.LogCaptureFixture) -> None:
    prob = STORE_P.replace("(:goal", "(:length (:serial 1) (:parallel 1))\n  (:goal")
    assert solve(tmp_path, STORE, prob, capsys) == ["(put h c s1 s2)"]
    assert any(":length" in r.getMessage() for r in caplog.records)


# IPC-2004 airport-ADL: forall-when effects over all segments; lifted, 2**k variants; bound, a handful.
RUNWAY = """\
(define (domain runway)
  (:requirements :typing :conditional-effects :negative-preconditions :equality)
  (:types plane seg)
  (:predicates (at ?a - plane ?s - seg) (link ?s1 ?s2 - seg) (shadow ?s - seg ?s2 - seg)
               (blocked ?s - seg ?a - plane))
  (:action move
    :parameters (?a - plane ?s1 ?s2 - seg)
    :precondition (and (at ?a ?s1) (link ?s1 ?s2) (not (= ?s1 ?s2)))
    :effect (and (at ?a ?s2) (not (at ?a ?s1))
                 (forall (?s - seg) (when (shadow ?s ?s2) (blocked ?s ?a)))
                 (forall (?s - seg) (when (and (shadow ?s ?s1) (not (shadow ?s ?s2))) (not (blocked ?s ?a)))))))
"""


def runway_problem(n: int) -> str:
    segs = " ".join(f"s{i}" for i in range(n))
    links = " ".join(f"(link s{i} s{i + 1})" for i in range(n - 1))
    shadows = " ".join(f"(shadow s{i} s{i + 1})" for i in range(n - 1))
    return f"""\
(define (problem runway-{n}) (:domain runway)
  (:objects a - plane {segs} - seg)
  (:init (at a s0) {links} {shadows})
  (:goal (and (at a s{n - 1}) (blocked s{n - 2} a) (not (blocked s0 a)))))
"""


def test_per_binding_compilation_is_kept_when_smaller(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    prob = runway_problem(6)  # 12 lifted effect conditions: past the bound, compiled per binding anyway
    small = runway_problem(4)  # 8 lifted conditions (81 lifted operators here); 3 linked bindings
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    d.write_text(RUNWAY)
    p.write_text(small)
    ops = [o for o in load_pddl(d, p).domain.operators if (o.pddl_name or o.name) == "move"]
    assert 0 < len(ops) <= 3 * 4  # per binding: at most a few variants per linked pair, not 2**8
    solve(tmp_path, RUNWAY, small, capsys)
    solve(tmp_path, RUNWAY, prob, capsys)


def test_ipc_check_script_reports_accepted_refused_and_validated(tmp_path: Path) -> None:
    import os
    import subprocess
    import sys

    root = Path(__file__).resolve().parent.parent
    good, bad = tmp_path / "pairs" / "store", tmp_path / "pairs" / "broken"
    good.mkdir(parents=True)
    bad.mkdir()
    (good / "domain.pddl").write_text(STORE)
    (good / "p01.pddl").write_text(STORE_P)
    (bad / "domain.pddl").write_text(STORE.replace("(:action put", "(:action put :vars (?x)", 1))
    (bad / "p01.pddl").write_text(STORE_P)
    (bad / "p02-domain.pddl").write_text(STORE)  # a per-instance domain wins over the folder's
    (bad / "p02.pddl").write_text(STORE_P)
    out = tmp_path / "table.md"
    env = {**os.environ, "PYTHONPATH": str(root / "src")}
    proc = subprocess.run([sys.executable, str(root / "benchmarks" / "ipc_check.py"), str(tmp_path / "pairs"),
                           "--time-limit", "10", "--problems", "2", "--out", str(out)], capture_output=True,
                          text=True, env=env,
                          timeout=200)
    assert proc.returncode == 0, proc.stderr
    rows = {ln.split("|")[1].strip(): [c.strip() for c in ln.split("|")[1:-1]]
            for ln in out.read_text().splitlines() if ln.startswith("| ") and not ln.startswith("| domain")}
    assert rows["store/p01"][2:5] == ["yes", "yes", "1"] and rows["store/p01"][8].startswith("valid")
    assert rows["broken/p01"][2:4] == ["no", "no"] and "refused" in rows["broken/p01"][-1]
    assert rows["broken/p02"][2:5] == ["yes", "yes", "1"]  # read with p02-domain.pddl
    summary = out.read_text().splitlines()[0]
    assert summary.startswith("3 pairs: accepted 2, solved 2, plans valid 2")
    if rows["store/p01"][6] == "yes":  # Fast Downward installed and solved it: the time ratio is reported
        assert float(rows["store/p01"][11]) > 0 and "median" in summary and "worst" in summary


# IPC-2008/2011 transport and elevators as stored in some public copies: the cost reads a function
# ((road-length ?a ?b)) that (:functions ...) never declares; the problem's :init gives its values.
ROADS = """\
(define (domain roads)
  (:requirements :typing :action-costs)
  (:types place truck)
  (:predicates (at ?t - truck ?p - place) (road ?a ?b - place))
  (:functions (total-cost) - number)
  (:action drive
    :parameters (?t - truck ?a ?b - place)
    :precondition (and (at ?t ?a) (road ?a ?b))
    :effect (and (not (at ?t ?a)) (at ?t ?b) (increase (total-cost) (road-length ?a ?b)))))
"""

ROADS_P = """\
(define (problem roads-1) (:domain roads)
  (:objects t - truck x y z - place)
  (:init (at t x) (road x y) (road y z) (road x z)
         (= (road-length x y) 2) (= (road-length y z) 3) (= (road-length x z) 9)
         (= (fuel-price x) 4) (= (total-cost) 0))
  (:goal (at t z))
  (:metric minimize (total-cost)))
"""


def test_undeclared_cost_function_is_declared_from_its_use(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                           caplog: pytest.LogCaptureFixture) -> None:
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    d.write_text(ROADS)
    p.write_text(ROADS_P)
    code = main(["plan", str(d), str(p), "--json", "--time-limit", "20"])
    out = capsys.readouterr()
    assert code == 0, out.err
    doc = json.loads(out.out)
    assert doc["plan"] == ["(drive t x y)", "(drive t y z)"] and doc["cost"] == 5.0  # 2 + 3 < 9
    msgs = [r.getMessage() for r in caplog.records]
    assert any("'road-length' is used in the effect of action drive but not declared" in m for m in msgs)
    assert any("'fuel-price', which the domain neither declares nor uses (ignored)" in m for m in msgs)


def test_undeclared_function_keeps_its_arity(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The first use fixes the arity: a later use with another arity is still an error naming both."""
    dom = ROADS.replace("(increase (total-cost) (road-length ?a ?b))",
                        "(increase (total-cost) (road-length ?a ?b)) (increase (total-cost) (road-length ?a))")
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    d.write_text(dom)
    p.write_text(ROADS_P)
    assert main(["plan", str(d), str(p)]) == 2
    err = capsys.readouterr().err
    assert "function 'road-length' takes 2 argument(s)" in err and "Traceback" not in err


# IPC-2011 floor-tile: the search's ties are broken by the order successors are generated in; in the domain's
# order of actions (as planners generate them) lama-first expands 92 states on p02, in name order 19,246.
TIES = """\
(define (domain ties)
  (:requirements :strips)
  (:predicates (start) (done) (via-zulu) (via-alpha))
  (:action zulu :parameters () :precondition (start) :effect (and (done) (via-zulu)))
  (:action alpha :parameters () :precondition (start) :effect (and (done) (via-alpha))))
"""

TIES_P = """\
(define (problem ties-1) (:domain ties)
  (:init (start))
  (:goal (done)))
"""


@pytest.mark.parametrize("search", ["lama", "gbfs"])
def test_tied_successors_follow_the_domains_order_of_actions(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                             search: str) -> None:
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    d.write_text(TIES)
    p.write_text(TIES_P)
    assert main(["plan", str(d), str(p), "--search", search]) == 0
    assert capsys.readouterr().out.split() == ["(zulu)"]  # declared first; "alpha" sorts first by name
    d.write_text(TIES.replace("(:action zulu", "(:action zz").replace("(:action alpha", "(:action zulu")
                 .replace("(:action zz", "(:action alpha"))
    assert main(["plan", str(d), str(p), "--search", search]) == 0
    assert capsys.readouterr().out.split() == ["(alpha)"]


# IPC-2002 STRIPS problems (zenotravel, driverlog, depots ...) end with (:metric minimize (total-time)).
def test_total_time_metric_is_ignored_with_a_warning(tmp_path: Path, capsys: pytest.CaptureFixture[str],
                                                     caplog: pytest.LogCaptureFixture) -> None:
    prob = STORE_P.replace("(:goal (on c s2)))", "(:goal (on c s2))\n  (:metric minimize (total-time)))")
    assert "total-time" in prob
    assert solve(tmp_path, STORE, prob, capsys) == ["(put h c s1 s2)"]
    assert any("(:metric minimize (total-time)) is ignored" in r.getMessage() for r in caplog.records)
    d, p = tmp_path / "d.pddl", tmp_path / "p.pddl"
    p.write_text(prob.replace("minimize (total-time)", "maximize (total-time)"))
    assert main(["plan", str(d), str(p)]) == 2  # any other metric: still refused, naming it
    assert "the metric (maximize ...) is not supported" in capsys.readouterr().err
