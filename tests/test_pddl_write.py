"""Writing PDDL back: round trips, abstraction levels, criticality files, the logistics generator."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.core.domain import Problem
from nowplan.errors import PDDLError
from nowplan.io.criticality import apply_criticality, criticality_text, parse_criticality
from nowplan.io.logistics_gen import generate_logistics
from nowplan.io.pddl_read import load_pddl, read_domain
from nowplan.io.pddl_write import domain_text, export_level, problem_text, write_pddl

from test_pddl_read import DATA, DOMAINS, GOOD_DOMAIN, GOOD_PROBLEM, write

CASES = [(d, p.name) for d in DOMAINS for p in sorted((DATA / d).glob("p*.pddl"))]


def same_model(a: Problem, b: Problem) -> None:
    assert a.domain == b.domain  # name, predicates, operators (with criticalities), types, constants
    assert [o.cost for o in a.domain.operators] == [o.cost for o in b.domain.operators]
    assert a.objects == b.objects and a.name == b.name
    assert a.init == b.init and a.goal == b.goal
    ga = [str(g) for c in a.domain.conflicts for g in getattr(c, "groups", ())]
    gb = [str(g) for c in b.domain.conflicts for g in getattr(c, "groups", ())]
    assert ga == gb


@pytest.mark.parametrize(("domain", "problem"), CASES)
def test_round_trip(tmp_path: Path, domain: str, problem: str) -> None:
    first = load_pddl(DATA / domain / "domain.pddl", DATA / domain / problem)
    dp, pp = write_pddl(first, tmp_path)
    again = load_pddl(dp, pp)
    same_model(first, again)
    # and writing is a fixpoint
    assert domain_text(again.domain) == dp.read_text()
    assert problem_text(again) == pp.read_text()


def test_round_trip_with_costs_equality_and_constants(tmp_path: Path) -> None:
    first = load_pddl(write(tmp_path, "d.pddl", GOOD_DOMAIN), write(tmp_path, "p.pddl", GOOD_PROBLEM))
    text = domain_text(first.domain)
    assert ":action-costs" in text and ":equality" in text and "(increase (total-cost) 0)" in text
    assert "(not (= ?y ?z))" in text and "(= a a)" not in problem_text(first)
    dp, pp = write_pddl(first, tmp_path / "out")
    same_model(first, load_pddl(dp, pp))


def test_round_trip_with_criticalities(tmp_path: Path) -> None:
    log = DATA / "logistics"
    first = load_pddl(log / "domain.pddl", log / "p01.pddl", log / "logistics.crit")
    crit = write(tmp_path, "x.crit", criticality_text(first.domain))
    dp, pp = write_pddl(first, tmp_path)
    same_model(first, load_pddl(dp, pp, crit))


def test_export_level_keeps_critical_and_static_preconditions() -> None:
    log = DATA / "logistics"
    prob = load_pddl(log / "domain.pddl", log / "p01.pddl", log / "logistics.crit")
    assert prob.domain.top_level == 1
    top, _ = export_level(prob, 1)
    flat, _ = export_level(prob, None)
    assert flat.count("(at ?truck ?loc)") == 2 and top.count("(at ?truck ?loc)") == 0
    assert top.count("(serves ?truck ?loc)") == 2  # static: kept at every level
    assert top.count("(in-city ?loc-from ?city)") == 1
    assert export_level(prob, 0)[0] == flat


# --------------------------------------------------------------------------- criticality files


def test_logistics_criticalities() -> None:
    log = DATA / "logistics"
    d = apply_criticality(read_domain(log / "domain.pddl"), log / "logistics.crit")
    crit = {(o.name, str(p.atom)): p.criticality for o in d.operators for p in o.preconditions}
    assert crit[("load-truck", "at(?truck, ?loc)")] == 1
    assert crit[("load-truck", "at(?pkg, ?loc)")] == 2
    assert crit[("unload-airplane", "at(?airplane, ?loc)")] == 1
    assert crit[("drive-truck", "at(?truck, ?loc-from)")] == 2
    assert d.top_level == 1


def test_specificity_and_negative_literals(tmp_path: Path) -> None:
    spec = write(tmp_path, "c.crit", """
        # comment
        default 3
        *    clear             2   ; every clear
        move clear             4
        move (clear ?z)        5
        *    (not (marked ?x)) 6
        move (not (= ?y ?z))   7
    """)
    d = apply_criticality(read_domain(write(tmp_path, "d.pddl", GOOD_DOMAIN)), spec)
    got = {(o.name, str(p.atom)): p.criticality for o in d.operators for p in o.preconditions}
    assert got == {
        ("move", "on(?x, ?y)"): 3,
        ("move", "clear(?x)"): 4,
        ("move", "clear(?z)"): 5,
        ("move", "not =(?y, ?z)"): 7,
        ("move", "not marked(?x)"): 6,
        ("mark", "clear(?x)"): 2,
    }


@pytest.mark.parametrize(
    ("line", "message"),
    [
        ("fly (on ?x ?y) 2", "unknown action 'fly'"),
        ("move shiny 2", "unknown predicate 'shiny'"),
        ("move (on ?a ?b) 2", "action 'move' has no precondition matching '(on ?a ?b)'"),
        ("mark on 2", "action 'mark' has no precondition matching 'on'"),
        ("move on two", "criticality must be a whole number"),
        ("move on 0", "criticality must be >= 1"),
        ("move (on ?x 2", "malformed literal"),
        ("move", "write 'ACTION"),
    ],
)
def test_criticality_errors_name_file_and_line(tmp_path: Path, line: str, message: str) -> None:
    path = write(tmp_path, "c.crit", f"# header\ndefault 2\n{line}\n")
    with pytest.raises(PDDLError) as info:
        apply_criticality(read_domain(write(tmp_path, "d.pddl", GOOD_DOMAIN)), path)
    assert str(info.value).startswith(f"{path}:3: ") and message in str(info.value)


def test_repeated_rule_and_missing_file(tmp_path: Path) -> None:
    path = write(tmp_path, "c.crit", "move on 2\nmove on 3\n")
    with pytest.raises(PDDLError, match=r"c\.crit:2: the same rule is given twice \(first on line 1\)"):
        apply_criticality(read_domain(write(tmp_path, "d.pddl", GOOD_DOMAIN)), path)
    with pytest.raises(PDDLError, match="criticality file not found"):
        parse_criticality(tmp_path / "none.crit")


# --------------------------------------------------------------------------- generator


def test_logistics_generator_is_seeded_and_loadable(tmp_path: Path) -> None:
    a = generate_logistics(3, 3, 2, 6, seed=7)
    assert a == generate_logistics(3, 3, 2, 6, seed=7)
    assert a != generate_logistics(3, 3, 2, 6, seed=8)
    prob = load_pddl(DATA / "logistics" / "domain.pddl", write(tmp_path, "g.pddl", a))
    kinds = sorted(prob.objects.values())
    assert kinds.count("package") == 6 and kinds.count("airplane") == 2 and kinds.count("truck") == 3
    assert kinds.count("airport") == 3 and kinds.count("location") == 6
    assert len(prob.goal) == 6
