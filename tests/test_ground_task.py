"""The ground task built in bulk from operator templates (planning/ground_task.py) against binding every action."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import pytest

from nowplan.core.atoms import Atom, Goal
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Action, StateFreeCost
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.grounding import Grounder
from nowplan.planning.ground_task import instances
from nowplan.planning.heuristics import ground_all, ground_task
from nowplan.planning.regression import PlannerConfig
from nowplan.planning.regression_search import _Search

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"
IPC = Path(__file__).resolve().parent / "data" / "pddl_ipc_style"
CASES = [
    (DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p02.pddl"),
    (DATA / "lights" / "domain.pddl", DATA / "lights" / "p02.pddl"),
    (DATA / "blocksworld" / "domain.pddl", DATA / "blocksworld" / "p02.pddl"),
    (DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl"),
    *[(IPC / f"{n}-domain.pddl", IPC / f"{n}-p01.pddl")
      for n in ("floortile", "miconic", "rooms", "transport", "zenotravel", "briefcase")],
]


@pytest.mark.parametrize("dom,prob", CASES, ids=lambda p: p.parent.name + "/" + p.name)
def test_bulk_task_equals_binding_each_action(dom, prob):
    """Same actions in the same order, same precondition and effect facts, twins and costs."""
    p = load_pddl(dom, prob)
    srch = _Search(p.domain, p.objects, p.init, flat_levels(), PlannerConfig(engine="regression"), None)
    task = ground_task(srch.grounder, srch.drop)
    ref = ground_all(srch.grounder, srch.drop)
    assert task.n == len(ref)
    T = p.domain.facts
    for k, ga in enumerate(ref):
        act = task.action(k)
        assert act.key == ga.action.key
        assert task.index[act.key] == k or ref[task.index[act.key]].action.key == act.key
        assert [(T.atoms[f], c) for f, c, _ in task.pre[k]] == list(ga.pre)
        for f, _, twin in task.pre[k]:
            a = T.atoms[f]
            assert twin == (T.id(a.negate()) if a.value is False else -1)
        assert [T.atoms[e] for e in task.effects[k]] == list(ga.effects)
        c = act.operator.cost  # a StateFreeCost is a number per instance; another callable reads the belief
        assert task.fixed_cost[k] == (act.cost(None) if isinstance(c, StateFreeCost) else
                                      None if callable(c) else float(c))
    assert [ga.action.key for ga in task.acts] == [ga.action.key for ga in ref]


@pytest.mark.parametrize("dom,prob", CASES, ids=lambda p: p.parent.name + "/" + p.name)
def test_task_actions_are_the_grounders(dom, prob):
    """One object per instance: the task's actions are those the goal-directed grounder makes."""
    p = load_pddl(dom, prob)
    g = Grounder(p.domain, p.objects, p.init)
    srch = _Search(p.domain, p.objects, p.init, flat_levels(), PlannerConfig(engine="regression"), None)
    task = ground_task(srch.grounder, srch.drop)
    for k in range(0, task.n, max(1, task.n // 40)):
        act = task.action(k)
        for e in act.effects():
            found = {id(a): a for a in g.achievers(e, lambda: None)}  # type: ignore[arg-type,return-value]
            assert isinstance(act, Action) and id(act) in found


@pytest.mark.parametrize("dom,prob", CASES, ids=lambda p: p.parent.name + "/" + p.name)
def test_fill_is_every_typed_binding_whose_statics_hold(dom, prob):
    """``_fill`` (joins, then typed objects; statics matched by the join not checked twice) against brute force."""
    p = load_pddl(dom, prob)
    g = Grounder(p.domain, p.objects, p.init)
    for op in p.domain.operators:
        pools = [g.objects_of(op.type_of(v)) for v in op.params]
        if math.prod(len(x) for x in pools) > 50_000:
            continue
        statics = [pr.atom for pr in op.preconditions if pr.atom.predicate in p.domain.static_predicates]
        want = set()
        for combo in itertools.product(*pools):
            b = dict(zip(op.params, combo, strict=True))
            if all(p.domain.holds(s.bind(b), p.init) for s in statics):
                want.add(combo)
        got = [tuple(b[v] for v in op.params) for b in g._fill(op, {})]
        assert len(got) == len(set(got)) and set(got) == want, op.name


@pytest.mark.parametrize("dom,prob", CASES, ids=lambda p: p.parent.name + "/" + p.name)
def test_achievers_read_off_the_task_equal_the_grounders(dom, prob):
    """Same achievers in the same order as unifying and completing each operator (the grounder without memo)."""
    p = load_pddl(dom, prob)
    srch = _Search(p.domain, p.objects, p.init, flat_levels(), PlannerConfig(engine="regression"), None)
    task = ground_task(srch.grounder, srch.drop)
    fast = Grounder(p.domain, p.objects, p.init)
    fast.use_task(task)
    T = p.domain.facts
    atoms = {T.atoms[e] for effs in task.effects for e in effs}
    atoms |= {a.negate() for a in list(atoms)}
    some = sorted(atoms)[:3]
    atoms |= {Atom(a.predicate, tuple("no-such-object" for _ in a.args), a.value) for a in some}  # not an object
    Grounder.memo = False
    try:
        slow = Grounder(p.domain, p.objects, p.init)
        read = 0
        wants = {}
        for a in sorted(atoms):
            groups = fast._task_groups(a)
            for i, _op, effs in fast._by_pred.get(a.predicate, ()):
                read += groups is not None and fast._task_achievers(i, effs, a, groups) is not None
            want = [x.key for x in slow.achievers(a, Goal(frozenset({a})))]
            got = [x.key for x in fast.achievers(a, Goal(frozenset({a})))]
            assert got == want, a
            wants[a] = want
        assert read > len(atoms) // 4  # the task answered most questions
    finally:
        Grounder.memo = True
    whole = 0
    for a, want in wants.items():
        if fast.task_answers(a, task):  # the compiled regression loop reads these off the task's adders
            whole += 1
            f = T.by_key[(a.predicate, a.args, a.value)]
            assert [task.action(k).key for k in dict.fromkeys(task.adders().get(f, ()))] == want, a
    assert whole > len(atoms) // 4
    assert not Grounder(p.domain, p.objects, p.init).task_answers(a, task)  # one that answers from no task


@pytest.mark.parametrize("dom,prob", CASES, ids=lambda p: p.parent.name + "/" + p.name)
def test_instances_are_fills_in_order(dom, prob):
    """The array-based enumeration of the task's instances gives ``_fill(op, {})``'s, in its order."""
    p = load_pddl(dom, prob)
    g = Grounder(p.domain, p.objects, p.init)
    for op in p.domain.operators:
        assert instances(g, op) == [tuple(b[v] for v in op.params) for b in g._fill(op, {})], op.name


def test_a_state_free_cost_that_fails_for_an_unused_instance_is_asked_lazily() -> None:
    """A PDDL cost function the :init leaves undefined for an instance no plan needs (IPC-2011
    elevators p12: move-up-slow between floors its lift never serves) must not fail the call: the
    instance's cost stays None in the ground task and is asked only if a search uses it."""
    from nowplan.core.atoms import atom
    from nowplan.core.domain import Domain, Predicate
    from nowplan.core.operators import Operator, Precondition, StateFreeCost
    from nowplan.core.atoms import Var
    from nowplan.core.state import State
    from nowplan.errors import ModelError
    from nowplan.planning.plan import PlanStatus
    from nowplan.planning.regression import plan

    x, y = Var("x"), Var("y")

    class Distance(StateFreeCost):
        def __call__(self, bindings, belief=None):
            if (bindings[x], bindings[y]) == ("c", "a"):
                raise ModelError("no distance given from c to a")
            return 2.0

    dom = Domain("hops", {"at": Predicate("at", 1), "link": Predicate("link", 2)},
                 (Operator("hop", (x, y), (Precondition(atom("at", x)), Precondition(atom("link", x, y))),
                           (atom("at", y), atom("at", x, value=False)), cost=Distance()),))
    init = State([atom("at", "a"), atom("link", "a", "b"), atom("link", "b", "c"), atom("link", "c", "a")])
    res = plan(dom, {o: None for o in "abc"}, init, Goal.of([atom("at", "c")]), flat_levels(),
               PlannerConfig(engine="regression", serialization=False, monotonic=False))
    assert res.status is PlanStatus.SOLVED and [s.action.key for s in res.plan.steps[1:]] == [
        ("hop", ("a", "b")), ("hop", ("b", "c"))]
