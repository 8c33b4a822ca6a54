"""Automatic criticalities (issue 18): Knoblock's ordered-monotonic hierarchies.

Unit tests on hand-made domains with known hierarchies (Tower of Hanoi in
Knoblock's per-disk encoding: one level per disk; typed logistics: packages
above vehicles, equal to the hand-written logistics.crit; blocksworld: one
level), a hypothesis property test that the derived levels satisfy the
ordered-monotonicity constraints on random domains, the round trip of the
printed file, the executive's refine-flat fallback, and the CLI end to end.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.acting.metrics import Outcome
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.cli import main
from nowplan.core.atoms import Atom, Goal, Var
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.registry import Episode
from nowplan.io.criticality import apply_criticality, hierarchy_text
from nowplan.io.pddl_read import read_domain
from nowplan.planning.abstraction import (
    LiteralClass,
    auto_criticality,
    changing_effects,
    derive_hierarchy,
    literal_levels,
    violations,
)
from nowplan.worlds.symbolic import SymbolicWorld

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "src" / "nowplan" / "data" / "pddl"
CLASSICAL = ROOT / "benchmarks" / "classical"
DOMAIN_FILES = sorted(SHIPPED.glob("*/domain.pddl")) + sorted(CLASSICAL.glob("*/domain.pddl"))
F, T = Var("from"), Var("to")


def _op(name: str, pre: list[Atom], eff: list[Atom], params: tuple[Var, ...] = (),
        types: tuple[str | None, ...] = ()) -> Operator:
    return Operator(name, params, tuple(Precondition(a, 1) for a in pre), tuple(eff), param_types=types)


def _crits(domain: Domain) -> dict[tuple[str, Atom], int]:
    return {(o.name, p.atom): p.criticality for o in domain.operators for p in o.preconditions}


def hanoi() -> Domain:
    """Knoblock's three-disk Tower of Hanoi: one move operator per disk, ``on-<disk>(peg)``."""
    disks = ("small", "medium", "large")
    ops = []
    for i, d in enumerate(disks):
        smaller = disks[:i]
        pre = [Atom(f"on-{d}", (F,))] + [Atom(f"on-{s}", (p,), False) for s in smaller for p in (F, T)]
        eff = [Atom(f"on-{d}", (F,), False), Atom(f"on-{d}", (T,))]
        ops.append(_op(f"move-{d}", pre, eff, (F, T), ("peg", "peg")))
    preds = {f"on-{d}": Predicate(f"on-{d}", 1, ("peg",)) for d in disks}
    return Domain("hanoi", preds, tuple(ops), types={"peg": None})


def test_hanoi_gives_one_level_per_disk() -> None:
    dom = hanoi()
    h = derive_hierarchy(dom)
    assert h.top == 2
    assert {str(c): lvl for c, lvl in h.levels.items()} == {
        "on-small(peg)": 0, "on-medium(peg)": 1, "on-large(peg)": 2}
    crit = _crits(auto_criticality(dom))
    # the moved disk's own position is kept at every level, smaller disks are details below
    assert crit[("move-large", Atom("on-large", (F,)))] == 3
    assert crit[("move-large", Atom("on-medium", (T,), False))] == 2
    assert crit[("move-large", Atom("on-small", (F,), False))] == 1
    assert crit[("move-small", Atom("on-small", (F,)))] == 3


def test_logistics_separates_packages_from_vehicles_as_the_hand_written_file() -> None:
    dom = read_domain(SHIPPED / "logistics" / "domain.pddl")
    h = derive_hierarchy(dom)
    levels = {str(c): lvl for lvl, cs in h.by_level().items() for c in cs}
    assert levels["at(package, place)"] == levels["in(package, truck)"] == 1
    assert levels["at(truck, place)"] == levels["at(airplane, airport)"] == 0
    assert {"in-city", "serves"} <= h.static
    auto = _crits(auto_criticality(dom))
    hand = _crits(apply_criticality(dom, SHIPPED / "logistics" / "logistics.crit"))
    assert auto == hand


def test_blocksworld_is_one_level() -> None:
    dom = read_domain(SHIPPED / "blocksworld" / "domain.pddl")
    assert derive_hierarchy(dom).top == 0
    assert auto_criticality(dom).top_level == 0


def test_a_class_no_operator_changes_is_static() -> None:
    """``at`` of a hoist never changes (depots): kept at every level, not a low level."""
    x, p = Var("x"), Var("p")
    dom = Domain(
        "hoists",
        {"at": Predicate("at", 2), "lifted": Predicate("lifted", 1), "clear": Predicate("clear", 1)},
        (
            _op("lift", [Atom("at", (Var("h"), p)), Atom("at", (x, p)), Atom("clear", (x,))],
                [Atom("lifted", (x,)), Atom("at", (x, p), False)], (Var("h"), x, p), ("hoist", "crate", "place")),
            _op("tidy", [], [Atom("clear", (x,))], (x,), ("crate",)),
        ),
        types={"hoist": None, "crate": None, "place": None},
    )
    h = derive_hierarchy(dom)
    assert LiteralClass("at", ("hoist", "place")) in h.static_classes()
    crit = _crits(auto_criticality(dom))
    assert crit[("lift", Atom("at", (Var("h"), p)))] == h.top + 1
    assert crit[("lift", Atom("clear", (x,)))] == 1  # below lift's own level


def test_an_effect_that_restates_a_precondition_constrains_no_level() -> None:
    """Rovers' ``communicate`` deletes and re-adds ``available`` and ``channel_free`` (deletes first, the
    add wins): no change.  Counted as effects they tie ``communicated`` to ``available``, which
    ``navigate`` needs, and the domain was one level; left out, navigation is below the samples and the
    samples below the communications."""
    dom = read_domain(CLASSICAL / "rovers" / "domain.pddl")
    comm = next(op for op in dom.operators if op.name == "communicate_soil_data")
    assert [e.predicate for e in changing_effects(comm)] == ["communicated_soil_data"]
    h = derive_hierarchy(dom)
    assert h.top == 2
    assert h.levels[h.members[LiteralClass("at", ("rover", "waypoint"))]] == 0
    assert h.levels[h.members[LiteralClass("communicated_soil_data", ("waypoint",))]] == 2
    assert LiteralClass("available", ("rover",)) in h.static_classes()
    assert violations(dom, literal_levels(dom, h)) == []
    # a delete that is not restated is a change: the precondition's value is not where the fluent ends
    x = Var("x")
    flip = _op("flip", [Atom("p", (x,))], [Atom("p", (x,), False)], (x,), ("a",))
    keep = _op("keep", [Atom("p", (x,))], [Atom("p", (x,), False), Atom("p", (x,))], (x,), ("a",))
    assert changing_effects(flip) == flip.effects
    assert changing_effects(keep) == ()


@pytest.mark.parametrize("path", DOMAIN_FILES, ids=lambda p: f"{p.parent.parent.name}-{p.parent.name}")
def test_printed_file_loads_back_to_the_same_criticalities(tmp_path: Path, path: Path) -> None:
    dom = read_domain(path)
    text = hierarchy_text(dom)
    f = tmp_path / "auto.crit"
    f.write_text(text)
    assert _crits(apply_criticality(dom, f)) == _crits(auto_criticality(dom))
    assert _crits(apply_criticality(dom, "auto")) == _crits(auto_criticality(dom))
    h = derive_hierarchy(dom)
    assert violations(dom, literal_levels(dom, h)) == []


# --------------------------------------------------------------------------- property

PREDS = ("p", "q", "r", "s", "u")


@st.composite
def domains(draw: st.DrawFn) -> Domain:
    """Random unary/nullary STRIPS domains over two types."""
    arity = {n: draw(st.integers(0, 1)) for n in PREDS}
    ptype = {n: draw(st.sampled_from(["a", "b"])) for n in PREDS}
    ops = []
    for i in range(draw(st.integers(1, 6))):
        params = (Var("x"),)
        t = draw(st.sampled_from(["a", "b"]))

        def lit(value: bool, t: str = t) -> Atom:
            n = draw(st.sampled_from(PREDS))
            return Atom(n, (Var("x"),) if arity[n] else (), value)

        pre = [lit(draw(st.booleans())) for _ in range(draw(st.integers(0, 3)))]
        eff = [lit(draw(st.booleans())) for _ in range(draw(st.integers(1, 2)))]
        ops.append(_op(f"o{i}", pre, eff, params, (t,)))
    preds = {n: Predicate(n, arity[n], (ptype[n],) * arity[n]) for n in PREDS}
    return Domain("random", preds, tuple(ops), types={"a": None, "b": None})


@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(domains())
def test_derived_hierarchy_is_ordered_monotonic(dom: Domain) -> None:
    h = derive_hierarchy(dom)
    lv = literal_levels(dom, h)
    # Knoblock's constraints: one level for an operator's effects, no precondition above it
    assert violations(dom, lv) == []
    for e, p in h.edges:
        assert h.levels[e] >= h.levels[p]
    # bottom-up layering: no empty level; each level above 0 is constrained by the one below it
    present = set(h.levels.values())
    assert present == set(range(h.top + 1)) or not present
    for lvl in present - {0}:
        assert any(h.levels[e] == lvl and h.levels[p] == lvl - 1 for e, p in h.edges)
    # HPN criticalities: a dropped precondition is strictly below its operator's effects
    auto = auto_criticality(dom)
    for op in auto.operators:
        k = h.effect_level(dom, op)
        for p in op.preconditions:
            if p.criticality <= h.top:
                lvl = h.level_of(dom, op, p.atom)
                assert lvl is not None and k is not None and lvl < k and p.criticality == lvl + 1


def test_the_checker_finds_a_broken_hierarchy() -> None:
    dom = hanoi()
    lv = literal_levels(dom, derive_hierarchy(dom))
    broken = {k: (2 - v if v is not None else None) for k, v in lv.items()}  # levels upside down
    assert violations(dom, broken)


# --------------------------------------------------------------------------- executive


def _trap() -> Problem:
    """The cheap abstract plan ``a1, a2`` cannot be refined: ``a1`` needs ``y``, whose achiever
    needs ``n``, which nothing reachable gives (``spin`` needs ``n`` itself); ``b`` is the way."""
    def op(name: str, pre: list[tuple[str, int]], eff: str, cost: float = 1.0) -> Operator:
        return Operator(name, (), tuple(Precondition(Atom(a), c) for a, c in pre), (Atom(eff),), cost=cost)

    dom = Domain(
        "trap",
        {n: Predicate(n, 0) for n in ("g", "x", "y", "n", "w")},
        (
            op("a1", [("y", 1)], "x"),
            op("a2", [("x", 2)], "g"),
            op("get-y", [("n", 2)], "y"),
            op("spin", [("n", 2)], "n"),
            op("b", [("w", 2)], "g", cost=5.0),
        ),
    )
    return Problem(dom, {}, State([Atom("w")]), Goal.of([Atom("g")], dom.rules), "trap")


def _run(problem: Problem, strategy: str) -> Outcome:
    ep = Episode(problem, SymbolicWorld(problem.domain, problem.init, seed=0), SymbolicBelief(problem.init), "t")
    return run_episode(ep, parse_strategy(strategy, time_limit=20.0), seed=0).outcome


def test_refine_flat_recovers_from_an_abstract_plan_that_cannot_be_refined() -> None:
    prob = _trap()
    assert prob.domain.top_level == 1
    # both recoveries reach the goal: refine-flat plans the goal concretely, plain hpn
    # backtracks (the unrefinable a1 is learnt as a nogood, acting/backtrack.py)
    assert _run(prob, "hpn+refine-flat") is Outcome.REACHED
    assert _run(prob, "hpn") is Outcome.REACHED


# --------------------------------------------------------------------------- CLI


def test_cli_criticality_prints_a_file_that_plan_accepts(capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    dom = SHIPPED / "logistics" / "domain.pddl"
    assert main(["criticality", str(dom)]) == 0
    text = capsys.readouterr().out
    assert "# level 1 (criticality 2): at(package, airport), at(package, place)" in text
    assert "load-truck (at ?truck ?loc) 1" in text
    f = tmp_path / "auto.crit"
    assert main(["criticality", str(dom), "--out", str(f)]) == 0
    assert f.read_text() == text
    p01 = str(SHIPPED / "logistics" / "p01.pddl")
    assert main(["plan", str(dom), p01, "--criticality", str(f), "--level", "top"]) == 0
    top_file = capsys.readouterr().out
    assert main(["plan", str(dom), p01, "--criticality", "auto", "--level", "top"]) == 0
    assert capsys.readouterr().out == top_file
    assert "drive-truck" not in top_file


@pytest.mark.parametrize("name", ["logistics", "gripper", "lights"])
def test_cli_run_with_auto_criticality_reaches_the_goal(capsys: pytest.CaptureFixture[str], name: str) -> None:
    d = SHIPPED / name
    code = main(["run", str(d / "domain.pddl"), str(d / "p02.pddl"), "--criticality", "auto", "--json"])
    assert code == 0, capsys.readouterr()


def test_cli_run_rejects_a_missing_criticality_file(capsys: pytest.CaptureFixture[str]) -> None:
    d = SHIPPED / "logistics"
    with pytest.raises(SystemExit) as exc:
        main(["run", str(d / "domain.pddl"), str(d / "p01.pddl"), "--criticality", "nope.crit"])
    assert exc.value.code == 2
    assert "nope.crit" in capsys.readouterr().err


# --------------------------------------------------------------------------- problems (run --criticality auto)


def _classical(domain: str, problem: str) -> Problem:
    from nowplan.io.pddl_read import load_pddl

    return load_pddl(CLASSICAL / domain / "domain.pddl", CLASSICAL / domain / f"{problem}.pddl", "auto")


def test_goal_stages_put_the_abstract_literals_first() -> None:
    from nowplan.planning.problem_hierarchy import goal_stages

    prob = _classical("driverlog", "p04")
    (stage,) = goal_stages(prob, derive_hierarchy(prob.domain))
    assert {a.predicate for a in stage.atoms} == {"at"}
    assert all(str(a.args[0]).startswith("package") for a in stage.atoms)
    assert stage.atoms < prob.goal.atoms


def test_reachability_statics_prune_only_abstract_steps() -> None:
    from nowplan.planning.reach_statics import add_reachability_statics
    from nowplan.planning.task import grounding

    prob = _classical("logistics", "p04")
    aug = add_reachability_statics(prob)
    load = aug.domain.operator_map["load-truck"]
    assert any(p.atom.predicate == "reachable-at" and p.criticality == aug.domain.max_criticality
               for p in load.preconditions)

    def keys(p: Problem, level: int) -> set[tuple[str, tuple[object, ...]]]:
        return {a.key for a in grounding(p.domain, p.objects, p.init, level).actions}

    assert keys(aug, -1) == keys(prob, -1)  # concrete: the same reachable actions
    top = prob.domain.top_level
    assert keys(aug, top) < keys(prob, top)  # abstract: trucks no longer serve other cities


def test_the_executive_achieves_the_stages_in_order() -> None:
    from nowplan.trace import Trace

    dom = Domain("two", {"a": Predicate("a", 0), "b": Predicate("b", 0)},
                 (Operator("set-a", (), (), (Atom("a"),)), Operator("set-b", (), (), (Atom("b"),))))
    goal = Goal.of([Atom("a"), Atom("b")], dom.rules)
    prob = Problem(dom, {}, State([]), goal, "two", stages=(Goal.of([Atom("b")], dom.rules),))
    ep = Episode(prob, SymbolicWorld(dom, prob.init, seed=0), SymbolicBelief(prob.init), "t")
    with Trace(None) as tr:
        m = run_episode(ep, parse_strategy("hpn"), seed=0, trace=tr)
    assert m.outcome is Outcome.REACHED
    assert [e["action"] for e in tr.events if e["event"] == "action"] == ["(set-b)", "(set-a)"]


@pytest.mark.parametrize(("domain", "problem"), [("logistics", "p05"), ("driverlog", "p04")])
def test_cli_run_auto_on_classical_problems_flat_planning_solves(
        capsys: pytest.CaptureFixture[str], domain: str, problem: str) -> None:
    """IPC logistics needs the reachability statics, driverlog the cycle check (refine-flat)."""
    d = CLASSICAL / domain
    code = main(["run", str(d / "domain.pddl"), str(d / f"{problem}.pddl"), "--criticality", "auto",
                 "--time-limit", "60"])
    assert code == 0, capsys.readouterr().out


def test_an_irreversible_concrete_step_makes_auto_plan_flat(caplog: pytest.LogCaptureFixture) -> None:
    """nomystery: driving spends fuel that nothing restores, so the abstract plan could strand
    the truck; zenotravel refuels and logistics drives back, so they keep their hierarchy."""
    from nowplan.planning.problem_hierarchy import prepare_problem

    with caplog.at_level("WARNING"):
        nomystery = prepare_problem(_classical("nomystery", "p01"))
    assert nomystery.domain.top_level == 0 and nomystery.stages == ()
    assert "deletes fuel(" in caplog.text
    for d in ("zenotravel", "logistics", "driverlog", "gripper"):
        assert prepare_problem(_classical(d, "p03")).domain.top_level == 1, d


def test_irreversible_step_is_sound_on_a_tiny_domain() -> None:
    from nowplan.planning.dead_ends import irreversible_step

    def dom(with_refill: bool, with_cool: bool = True) -> Problem:
        ops = [Operator("burn", (), (Precondition(Atom("full"), 1),), (Atom("full", (), False), Atom("hot")))]
        if with_cool:  # a second use of 'full': losing it loses 'cold'
            ops.append(Operator("cool", (), (Precondition(Atom("full"), 1),), (Atom("cold"),)))
        if with_refill:
            ops.append(Operator("refill", (), (Precondition(Atom("hot"), 1),), (Atom("full"),)))
        d = Domain("fuel", {n: Predicate(n, 0) for n in ("full", "hot", "cold")}, tuple(ops))
        return Problem(d, {}, State([Atom("full")]), Goal.of([Atom("hot")], d.rules), "fuel")

    found = irreversible_step(dom(False), lambda a: True)
    assert found is not None and found.atom == Atom("full") and found.action.name == "burn"
    assert irreversible_step(dom(True), lambda a: True) is None
    assert irreversible_step(dom(False), lambda a: False) is None  # only steps below the top count
    # 'full' only ever served 'burn', whose 'hot' stays true: losing it is harmless
    assert irreversible_step(dom(False, with_cool=False), lambda a: True) is None


ATOMS = ("a", "b", "c", "d")


@st.composite
def fuel_problems(draw: st.DrawFn) -> Problem:
    lit = st.sampled_from(ATOMS)
    ops = []
    for i in range(draw(st.integers(1, 5))):
        pre = draw(st.lists(lit, max_size=2, unique=True))
        add = draw(st.lists(lit, max_size=2, unique=True))
        dele = [x for x in draw(st.lists(lit, min_size=1, max_size=2, unique=True)) if x not in add]
        eff = [Atom(x, (), False) for x in dele] + [Atom(x) for x in add]
        ops.append(Operator(f"o{i}", (), tuple(Precondition(Atom(x), 1) for x in pre), tuple(eff)))
    d = Domain("rnd", {n: Predicate(n, 0) for n in ATOMS}, tuple(ops))
    init = State([Atom(x) for x in draw(st.lists(lit, max_size=3, unique=True))])
    return Problem(d, {}, init, Goal.of([Atom(draw(lit))], d.rules), "rnd")


def _successors(prob: Problem, s: frozenset[str]) -> list[tuple[str, frozenset[str]]]:
    out = []
    for op in prob.domain.operators:
        if all(p.atom.predicate in s for p in op.preconditions):
            dels = {e.predicate for e in op.effects if e.value is False}
            adds = {e.predicate for e in op.effects if e.value is True}
            out.append((op.name, frozenset((s - dels) | adds)))
    return out


def _reachable(prob: Problem, start: frozenset[str]) -> set[frozenset[str]]:
    seen, todo = {start}, [start]
    while todo:  # at most 2^4 states
        for _, t in _successors(prob, todo.pop()):
            if t not in seen:
                seen.add(t)
                todo.append(t)
    return seen


@settings(max_examples=200, deadline=None)
@given(fuel_problems())
def test_an_irreversible_step_really_loses_its_atom_for_ever(prob: Problem) -> None:
    from nowplan.planning.dead_ends import irreversible_step

    found = irreversible_step(prob, lambda a: True)
    if found is None:
        return
    init = frozenset(a.predicate for a in prob.init.atoms() if a.value is True)
    for s in _reachable(prob, init):
        for name, t in _successors(prob, s):
            if name == found.action.name:
                assert all(found.atom.predicate not in u for u in _reachable(prob, t))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_refine_flat_survives_failing_actions(seed: int, capsys: pytest.CaptureFixture[str]) -> None:
    """A failed action is news, not a cycle: refine-flat used to count the unchanged state after
    each failure as a revisit and to plan marsupial flat after a failed refinement (no flat plan
    within the node limit: 0 of 9 in the fault benchmark); it now backtracks like hpn."""
    import json

    assert main(["run", "--domain", "marsupial", "--scenario", "single-3", "--strategy", "hpn+refine-flat",
                 "--seed", str(seed), "--failure-prob", "0.25", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["outcome"] == "reached", doc.get("reason")
