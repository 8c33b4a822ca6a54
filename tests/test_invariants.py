"""Mutex invariant inference: the groups found, their soundness, and their use in regression."""

from __future__ import annotations

from nowplan.core.atoms import Atom, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl, read_domain
from nowplan.planning.invariants import (
    MutexGroup,
    MutexRule,
    find_invariants,
    infer_mutexes,
    initially_valid,
)
from nowplan.planning.regression import PlannerConfig, plan

from test_pddl_read import DATA


def groups(name: str) -> set[str]:
    return {str(g) for g in find_invariants(read_domain(DATA / name / "domain.pddl"))}


def test_logistics_groups() -> None:
    assert "{at[0], in[0]}" in groups("logistics")


def test_blocksworld_groups() -> None:
    g = groups("blocksworld")
    assert "{holding[0], on[0], ontable[0]}" in g
    assert "{handempty, holding}" in g


def test_gripper_groups() -> None:
    assert {"{at[0], carry[0]}", "{at-robby}", "{carry[1], free[0]}"} <= groups("gripper")


def members(domain: Domain) -> set[str]:
    return {pred for g in find_invariants(domain) for pred, _ in g.members}


def test_no_false_invariants_on_unbalanced_operators() -> None:
    x, y, z = Var("x"), Var("y"), Var("z")
    preds = {"p": Predicate("p", 1), "q": Predicate("q", 1), "r": Predicate("r", 2)}
    # 'spawn' adds p without deleting anything: no group may contain p
    ops = (
        Operator("spawn", (x,), (), (atom("p", x),)),
        Operator("swap", (x,), (Precondition(atom("p", x)),), (atom("p", x, value=False), atom("q", x))),
    )
    assert "p" not in members(Domain("d", preds, ops))
    # a delete that is not a precondition does not balance an add
    ops2 = (Operator("move", (x, y), (), (atom("p", x, value=False), atom("p", y))),)
    assert "p" not in members(Domain("d", preds, ops2))
    # two adds with one key need two deleted atoms, not one
    ops3 = (
        Operator(
            "split", (x, y, z), (Precondition(atom("r", x, y)),),
            (atom("r", x, y, value=False), atom("r", x, z), atom("r", x, y)),
        ),
    )
    assert "r" not in members(Domain("d", preds, ops3))
    # ... while one add balanced by a required delete is fine
    ops4 = (
        Operator("move", (x, y, z), (Precondition(atom("r", x, y)),),
                 (atom("r", x, y, value=False), atom("r", x, z))),
    )
    assert "{r[0]}" in {str(g) for g in find_invariants(Domain("d", preds, ops4))}


def test_initial_state_check() -> None:
    g = MutexGroup(frozenset({("at", 0), ("in", 0)}))
    assert initially_valid(g, [atom("at", "p", "l1"), atom("in", "q", "t")])
    assert not initially_valid(g, [atom("at", "p", "l1"), atom("in", "p", "t")])
    # the group is dropped when the initial state breaks it
    log = DATA / "logistics"
    dom = read_domain(log / "domain.pddl")
    bad = State([atom("at", "pkg1", "a"), atom("at", "pkg1", "b")])
    assert "{at[0], in[0]}" not in {str(x) for x in infer_mutexes(dom, bad)}


def test_conflict_rule() -> None:
    rule = MutexRule([MutexGroup(frozenset({("at", 0), ("in", 0)})),
                      MutexGroup(frozenset({("handempty", None), ("holding", None)}))])
    assert rule(atom("at", "p", "l1"), atom("at", "p", "l2"))
    assert rule(atom("at", "p", "l1"), atom("in", "p", "t"))
    assert not rule(atom("at", "p", "l1"), atom("at", "q", "l1"))
    assert not rule(atom("at", "p", "l1"), atom("at", "p", "l1"))
    assert not rule(atom("at", "p", "l1"), atom("at", "p", "l2", value=False))
    assert rule(atom("handempty"), atom("holding", "a"))
    assert rule(atom("holding", "b"), atom("holding", "a"))
    assert not rule(atom("clear", "a"), atom("holding", "a"))


def test_load_pddl_adds_the_rule_and_it_prunes() -> None:
    log = DATA / "logistics"
    with_m = load_pddl(log / "domain.pddl", log / "p03.pddl")
    without = load_pddl(log / "domain.pddl", log / "p03.pddl", mutexes=False)
    assert any(isinstance(c, MutexRule) for c in with_m.domain.conflicts)
    assert without.domain.conflicts == ()
    assert with_m.domain.rules.atoms_conflict(atom("at", "pkg1", "city1-loc1"), atom("in", "pkg1", "plane1"))
    cfg = PlannerConfig(time_limit=30, serialization=False, monotonic=False, engine="regression")
    r1 = plan(with_m.domain, with_m.objects, with_m.init, with_m.goal, flat_levels(), cfg)
    r2 = plan(without.domain, without.objects, without.init, without.goal, flat_levels(), cfg)
    assert r1.solved and r2.solved
    # the same optimal search (A*, admissible pruning) needs far fewer expansions with mutexes
    assert r1.plan is not None and r2.plan is not None
    assert r1.plan.cost() == r2.plan.cost()
    assert r1.expanded * 5 < r2.expanded, (r1.expanded, r2.expanded)


def test_mutexes_hold_in_every_reachable_state() -> None:
    """Breadth-first over blocksworld p02's state space: every group holds everywhere."""
    bw = DATA / "blocksworld"
    prob = load_pddl(bw / "domain.pddl", bw / "p02.pddl")
    found = infer_mutexes(prob.domain, prob.init)
    from nowplan.planning.grounding import Grounder

    grounder = Grounder(prob.domain, prob.objects, prob.init)
    actions = [op.instantiate(b) for op in prob.domain.operators for b in grounder._fill(op, {})]
    seen = {prob.init}
    frontier = [prob.init]
    while frontier:
        s = frontier.pop()
        for g in found:
            assert initially_valid(g, s.atoms()), (g, s)
        for a in actions:
            if all(prob.domain.holds(p, s) for p in a.preconditions()):
                t = s.apply(a.effects())
                if t not in seen:
                    seen.add(t)
                    frontier.append(t)
    assert len(seen) > 100


def test_atom_order_is_irrelevant() -> None:
    rule = MutexRule([MutexGroup(frozenset({("on", 0), ("ontable", 0), ("holding", 0)}))])
    a, b = Atom("on", ("a", "b")), Atom("holding", ("a",))
    assert rule(a, b) and rule(b, a)
