"""The regression A*'s compiled loop (regression_native.py, _kernel_regress.c) against the Python loop.

Both must return the same status, the same plan with the same pre-images and the same node
counts, on the property test's random STRIPS families at every level and on the bundled PDDL
problems; and the compiled loop must really have run (a test that compares the Python loop with
itself cannot fail).  Where it cannot run a call it says so by returning ``None``.
"""

from __future__ import annotations

import itertools
from dataclasses import replace

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.core.atoms import Atom, Goal, Var
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import regression_native
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.planning.regression_search import _Search
from tests.kernel_support import PDDL, PROBLEMS
from tests.test_planner_property import FAMILIES, QUICK, check_contract, level_maps, witness_reaches_goal

needs_loop = pytest.mark.skipif(not regression_native.available(),
                                reason="the regression loop's kernel is not built (or NOWPLAN_PURE_PYTHON is set)")
pytestmark = needs_loop

CONFIG = replace(QUICK, heuristic="hadd", engine="regression")


def _steps(res):
    if res.plan is None:
        return None
    return [(None if s.action is None else s.action.key, frozenset(s.goal.atoms)) for s in res.plan.steps]


class _Count:
    """Wraps regression_native.run: how many calls the compiled loop answered."""

    def __init__(self) -> None:
        self.ran = 0
        self.real = regression_native.run

    def __call__(self, *args):
        out = self.real(*args)
        if out is not None:
            self.ran += 1
        return out


def _both(monkeypatch, *args):
    count = _Count()
    monkeypatch.setattr(regression_native, "run", count)
    out = []
    for native in (False, True):
        monkeypatch.setattr(_Search, "native", native)
        out.append(plan(*args))
    return out[0], out[1], count.ran


def _same(py, c, what=""):
    assert c.status is py.status, (what, c.reason, py.reason)
    assert c.reason == py.reason, what
    assert _steps(c) == _steps(py), what
    assert (c.expanded, c.generated) == (py.expanded, py.generated), what


@pytest.mark.parametrize("family", sorted(set(FAMILIES) - {"hanoi"}))
@pytest.mark.timeout(300, method="thread")
@settings(max_examples=10, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_the_compiled_loop_searches_as_the_python_loop(family, data):
    case = data.draw(FAMILIES[family], label="case")
    witness_reaches_goal(case)
    shortcuts = data.draw(st.booleans(), label="shortcuts")
    config = replace(CONFIG, serialization=shortcuts, monotonic=shortcuts,
                     max_nodes=data.draw(st.sampled_from([20, 1_000]), label="max_nodes"),
                     held_rewrites=data.draw(st.booleans(), label="held_rewrites"),
                     h2=data.draw(st.booleans(), label="h2"))
    objects = {o: None for o in case.objects}
    for name, levels in data.draw(level_maps(case), label="levels"):
        with pytest.MonkeyPatch.context() as mp:
            py, c, _ = _both(mp, case.domain, objects, case.init, case.goal, levels, config)
        _same(py, c, name)
        if c.status is PlanStatus.SOLVED:
            check_contract(case, levels, c, concrete=name == "flat")


@pytest.mark.parametrize("h2", [False, True], ids=["", "h2"])
@pytest.mark.parametrize("domain,problem", PROBLEMS)
def test_bundled_pddl_problems_plan_alike(monkeypatch, domain, problem, h2):
    p = load_pddl(str(PDDL / domain / "domain.pddl"), str(PDDL / domain / problem))
    py, c, ran = _both(monkeypatch, p.domain, p.objects, p.init, p.goal, flat_levels(),
                       replace(CONFIG, max_nodes=3_000, serialization=False, monotonic=False, h2=h2))
    _same(py, c, problem)
    assert ran >= 1, "the compiled loop never ran"


IPC_STYLE = PDDL.parents[3] / "tests" / "data" / "pddl_ipc_style"


@pytest.mark.parametrize("h2", [False, True], ids=["", "h2"])
@pytest.mark.parametrize("name", ["transport", "floortile", "zenotravel", "briefcase"])
def test_ipc_style_problems_with_action_costs_plan_alike(monkeypatch, name, h2):
    """Costs from static numeric functions (a StateFreeCost per action): the ground h_add and the loop
    (with h2 pruning too: the compiled loop drops the same subgoals)."""
    p = load_pddl(str(IPC_STYLE / f"{name}-domain.pddl"), str(IPC_STYLE / f"{name}-p01.pddl"))
    py, c, ran = _both(monkeypatch, p.domain, p.objects, p.init, p.goal, flat_levels(),
                       replace(CONFIG, max_nodes=3_000, serialization=False, monotonic=False, h2=h2))
    _same(py, c, name)
    assert ran >= 1, "the compiled loop never ran"


def test_the_loop_runs_on_a_blocks_problem():
    """A held goal fact undone and re-achieved (test_deferred's case), through the compiled loop."""
    from tests.test_deferred import BLOCKS

    init = State([Atom("on", ("a", "b")), Atom("ontable", ("b",)), Atom("ontable", ("c",)),
                  Atom("clear", ("a",)), Atom("clear", ("c",)), Atom("handempty", ())])
    goal = Goal.of([Atom("on", ("a", "b")), Atom("on", ("b", "c"))])
    with pytest.MonkeyPatch.context() as mp:
        py, c, ran = _both(mp, BLOCKS, {o: None for o in "abc"}, init, goal, flat_levels(),
                           replace(CONFIG, serialization=False, monotonic=False))
    assert ran == 1
    _same(py, c)
    assert c.status is PlanStatus.SOLVED and len(c.plan) == 6


def test_a_level_map_with_overrides_runs_in_the_loop():
    """stack(a, b) at level 1 (its preconditions dropped), the rest concrete: the call asks each fact's
    templates for itself (set_local_achievers) and still plans as the Python loop."""
    from nowplan.core.levels import LevelMap
    from tests.test_deferred import BLOCKS

    init = State([Atom("on", ("a", "b")), Atom("ontable", ("b",)), Atom("ontable", ("c",)),
                  Atom("clear", ("a",)), Atom("clear", ("c",)), Atom("handempty", ())])
    goal = Goal.of([Atom("on", ("a", "b")), Atom("on", ("b", "c"))])
    levels = LevelMap(0, frozenset({(("stack", ("a", "b")), 1)}))
    cfg = replace(CONFIG, serialization=False, monotonic=False)
    with pytest.MonkeyPatch.context() as mp:
        py, c, ran = _both(mp, BLOCKS, {o: None for o in "abc"}, init, goal, levels, cfg)
        flat_py, flat_c, flat_ran = _both(mp, BLOCKS, {o: None for o in "abc"}, init, goal, flat_levels(), cfg)
    assert ran == 1 and flat_ran == 1
    _same(py, c)
    _same(flat_py, flat_c)
    assert c.status is PlanStatus.SOLVED and len(c.plan) < len(flat_c.plan)  # the override changed the search


x = Var("x")
HALF = Domain(
    "half", {"p": Predicate("p", 1), "q": Predicate("q", 1)},
    (Operator("make", (x,), (Precondition(Atom("q", (x,)), 1),), (Atom("p", (x,)),), cost=0.5),
     Operator("prep", (x,), (), (Atom("q", (x,)),), cost=1.0)),
)


def test_fractional_estimates_run_in_python(monkeypatch):
    """h_add values of 1.5 would be summed in another order in C: the call runs in Python, alike."""
    goal = Goal.of([Atom("p", ("a",)), Atom("p", ("b",))])
    py, c, ran = _both(monkeypatch, HALF, {"a": None, "b": None}, State([]), goal, flat_levels(),
                       replace(CONFIG, serialization=False, monotonic=False))
    assert ran == 0
    _same(py, c)
    assert c.status is PlanStatus.SOLVED and len(c.plan) == 4


def test_the_loop_refuses_bad_ids():
    mod = regression_native._module()
    assert mod is not None
    loop = mod.Regressor(False)
    loop.add_fact(0, [])
    with pytest.raises(ValueError):
        loop.add_action([0, 5], [], False, [], 1.0, [5])  # fact 5 was never added
    with pytest.raises(IndexError):
        loop.set_achievers(3, [])
    with pytest.raises(ValueError):
        loop.search([7], [0.0], lambda f: True, lambda f: False, None, 1.0, 10, False, None, [], False, None, None)
    assert loop.facts == 1 and loop.actions == 0


def _not_held_and_down(a: Atom, b: Atom) -> bool:
    """A plain (pairwise) rule: a block held is neither on the table nor under another block."""
    if a.predicate != "holding" or a.value is not True or b.value is not True:
        return False
    return (b.predicate == "ontable" and b.args == a.args) or (b.predicate == "on" and b.args[1] == a.args[0])


def test_plain_conflict_rules_run_in_the_loop() -> None:
    from tests.test_deferred import BLOCKS

    dom = Domain(BLOCKS.name + "-plain", dict(BLOCKS.predicates), BLOCKS.operators,
                 conflicts=(_not_held_and_down,))
    assert dom.facts.plain
    init = State([Atom("on", ("a", "b")), Atom("ontable", ("b",)), Atom("ontable", ("c",)),
                  Atom("clear", ("a",)), Atom("clear", ("c",)), Atom("handempty", ())])
    for goal in (Goal.of([Atom("on", ("a", "b")), Atom("on", ("b", "c"))]),
                 Goal.of([Atom("on", ("c", "a")), Atom("ontable", ("b",))])):
        for shortcuts in (False, True):
            cfg = replace(CONFIG, serialization=shortcuts, monotonic=shortcuts)
            with pytest.MonkeyPatch.context() as mp:
                py, c, ran = _both(mp, dom, {o: None for o in "abc"}, init, goal, flat_levels(), cfg)
            assert ran >= 1
            _same(py, c, str(goal))
            assert c.status is PlanStatus.SOLVED


def test_the_tidy_house_plans_alike(monkeypatch):
    """The held-out tidy house (plain conflict rules, a last-seen belief), its place cost as the
    example has it (a plain callable: costed per call) and declared a StateFreeCost (a number per
    ground action): its top-level and flat calls."""
    from dataclasses import replace as dc_replace

    from nowplan.core.levels import LevelMap
    from nowplan.core.operators import StateFreeCost
    from tests.helpers import example_spec

    example_spec(monkeypatch, "tidy")
    from tidy_domain.scenarios import problem

    p, belief = problem(0, "tidy")

    class Free(StateFreeCost):
        def __init__(self, fn):
            self.fn = fn

        def __call__(self, bindings, belief=None):
            return self.fn(bindings, None)

    ops = tuple(dc_replace(op, cost=Free(op.cost)) if callable(op.cost) else op for op in p.domain.operators)
    for dom, levels in itertools.product((dc_replace(p.domain, operators=ops), p.domain),
                                         (LevelMap(p.domain.top_level), flat_levels())):
        cfg = replace(CONFIG, max_nodes=2_000, shortcut_nodes=500)
        with pytest.MonkeyPatch.context() as mp:
            py, c, ran = _both(mp, dom, p.objects, belief, p.goal, levels, cfg)
        assert ran >= 1, str(levels)
        _same(py, c, str(levels))


class _Ranks:
    """A stand-in for the loop that keeps what ``set_rank`` is given."""

    def __init__(self) -> None:
        self.rank: list[int] = []

    def set_rank(self, rank: list[int], start: int = 0) -> None:
        assert start + len(rank) >= len(self.rank) and start <= len(self.rank)
        self.rank[start:] = rank


@pytest.mark.parametrize("gap", [1, 3, 1 << 12])
@given(batches=st.lists(st.lists(st.tuples(st.sampled_from("abc"), st.integers(0, 6), st.booleans()),
                                 min_size=1, max_size=6), min_size=1, max_size=12))
@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
def test_new_facts_are_ranked_as_the_table_sorts_them(monkeypatch, gap, batches):
    """Facts arrive in batches (as a search meets them); after each, the ranks order every fact as
    ``FactTable.sorted`` does, whether a new fact fits between its neighbours or all are ranked again."""
    from nowplan.core.atoms import Rules
    from nowplan.core.facts import FactTable

    monkeypatch.setattr(regression_native, "_GAP", gap)
    table = FactTable(Rules())
    comp = regression_native.Compiled.__new__(regression_native.Compiled)
    comp.table, comp.loop, comp._sorted, comp._ranks = table, _Ranks(), [], []
    seen = 0
    for batch in batches:
        for p, x, v in batch:
            table.id(Atom(p, (f"o{x}",), v))
        n = len(table.atoms)
        if n > seen:
            comp._rank(seen, n)
            seen = n
        rank = comp.loop.rank
        assert len(set(rank)) == n
        assert sorted(range(n), key=rank.__getitem__) == table.sorted(range(n))


def test_facts_the_task_answers_for_get_their_achievers_in_the_loop(monkeypatch):
    """On a classical problem most facts' achievers are read off the ground task by the loop itself
    (task_achievers), and the plan is still the Python loop's."""
    from nowplan.planning.grounding import Grounder

    seen = {True: 0, False: 0}
    real = Grounder.task_answers

    def counted(self, target, task):
        out = real(self, target, task)
        seen[out] += 1
        return out

    monkeypatch.setattr(Grounder, "task_answers", counted)
    p = load_pddl(str(PDDL / "logistics" / "domain.pddl"), str(PDDL / "logistics" / "p02.pddl"))
    py, c, ran = _both(monkeypatch, p.domain, p.objects, p.init, p.goal, flat_levels(),
                       replace(CONFIG, max_nodes=3_000, serialization=False, monotonic=False))
    _same(py, c)
    assert ran >= 1 and c.status is PlanStatus.SOLVED
    assert seen[True] > 2 * seen[False], seen


def test_h2_prunes_in_both_loops(monkeypatch):
    """Depots (benchmarks/classical p01): h2 drops the subgoals holding a crate in a hoist and on a
    pallet (a flat A* expands 1,202 nodes without, 9 with); the compiled loop drops the same ones."""
    d = PDDL.parents[3] / "benchmarks" / "classical" / "depots"
    p = load_pddl(str(d / "domain.pddl"), str(d / "p01.pddl"))
    cfg = replace(CONFIG, max_nodes=20_000, serialization=False, monotonic=False, prune=False)
    off_py, off_c, _ = _both(monkeypatch, p.domain, p.objects, p.init, p.goal, flat_levels(), cfg)
    on_py, on_c, ran = _both(monkeypatch, p.domain, p.objects, p.init, p.goal, flat_levels(), replace(cfg, h2=True))
    _same(off_py, off_c)
    _same(on_py, on_c)
    assert ran >= 1, "the compiled loop never ran"
    assert on_c.status is PlanStatus.SOLVED and len(on_c.plan) == len(off_c.plan)
    assert on_c.expanded * 10 < off_c.expanded
