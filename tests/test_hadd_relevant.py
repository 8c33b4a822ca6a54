"""Goal-relevant, incremental h_add (planning/hadd_relevant.py) against one exploration of every action."""

from __future__ import annotations

import math
import random
from pathlib import Path

import pytest

from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.hadd_kernel import KernelHadd, kernel_hadd
from nowplan.planning.hadd_relevant import RelevantHadd
from nowplan.planning.native import kernel_class
from nowplan.planning.heuristics import ground_task, hadd_ids
from nowplan.planning.regression import PlannerConfig
from nowplan.planning.regression_search import _Search

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"
CASES = [("logistics", "p02", True), ("logistics", "p03", False), ("lights", "p02", False),
         ("blocksworld", "p02", False), ("gripper", "p01", False)]


def _walk(prob, steps: int, rng: random.Random) -> list[State]:
    """States along a random walk of applicable ground actions from the initial state."""
    srch = _Search(prob.domain, prob.objects, prob.init, flat_levels(), PlannerConfig(), None)
    acts = [ga.action for ga in ground_task(srch.grounder, srch.drop).acts]
    states = [prob.init]
    s = prob.init
    for _ in range(steps):
        ok = [a for a in acts if all(prob.domain.holds(p, s) for p in a.preconditions())]
        if not ok:
            break
        s = s.apply(rng.choice(ok).effects())
        states.append(s)
    return states


@pytest.mark.parametrize("domain,problem,crit", CASES)
def test_relevant_hadd_equals_the_full_exploration_along_a_walk(domain, problem, crit):
    """Every fact's value equals hadd_ids', call after call (the memo carried over and synced)."""
    d = DATA / domain
    prob = load_pddl(d / "domain.pddl", d / f"{problem}.pddl", d / "logistics.crit" if crit else None)
    rng = random.Random(7)
    states = _walk(prob, 12, rng)
    tops = sorted({flat_levels().top, prob.domain.top_level})
    kept = dropped = 0
    for s in states:
        for top in tops:
            srch = _Search(prob.domain, prob.objects, s, LevelMap(top), PlannerConfig(), None)
            acts = ground_task(srch.grounder, srch.drop).acts
            over = LevelMap(top)
            if top > flat_levels().top:  # an abstract call that refines one step, as HPN's do
                over = LevelMap(top).next_level(rng.choice(acts).action)
            for levels in (LevelMap(top), over):
                srch = _Search(prob.domain, prob.objects, s, levels, PlannerConfig(), None)
                full = hadd_ids(srch.grounder, levels, srch.drop, srch.cost)
                rel = RelevantHadd(srch.grounder, levels, srch.drop, srch.cost)
                facts = list(range(len(srch.table.atoms)))
                rng.shuffle(facts)  # the order facts are asked in must not matter
                for f in facts:
                    a = srch.table.atoms[f]
                    if a.predicate in srch.drop or srch.fholds(f):
                        continue
                    assert rel.get(f) == full.get(f, math.inf), (a, levels)
                kept, dropped = rel.memo.kept_batches, rel.memo.dropped_batches
    assert kept > 0 and dropped > 0  # the memo both carried values over and dropped stale ones


def test_two_calls_alive_at_once_each_get_their_own_values():
    """A call made while another is alive must not leave the shared memo wrong for the first."""
    d = DATA / "logistics"
    prob = load_pddl(d / "domain.pddl", d / "p03.pddl", d / "logistics.crit")
    s1, s2 = _walk(prob, 6, random.Random(3))[::5][:2]
    levels = LevelMap(prob.domain.top_level)
    calls = [_Search(prob.domain, prob.objects, s, levels, PlannerConfig(), None) for s in (s1, s2)]
    rels = [RelevantHadd(c.grounder, levels, c.drop, c.cost) for c in calls]
    fulls = [hadd_ids(c.grounder, levels, c.drop, c.cost) for c in calls]
    compared = 0
    for _ in range(2):
        for c, rel, full in zip(calls, rels, fulls):  # alternate between the two calls
            for f in range(len(c.table.atoms)):
                if c.table.atoms[f].predicate not in c.drop and not c.fholds(f):
                    assert rel.get(f) == full.get(f, math.inf)
                    compared += 1
    assert compared > 0 and s1 != s2


def test_regression_plans_with_the_relevant_hadd(monkeypatch):
    """Without the kernel the regression search's h_add is the relevant one; with it, the kernel's."""
    d = DATA / "logistics"
    prob = load_pddl(d / "domain.pddl", d / "p02.pddl")
    srch = _Search(prob.domain, prob.objects, prob.init, flat_levels(), PlannerConfig(heuristic="hadd"), None)
    assert isinstance(srch.hadd, KernelHadd if kernel_class() is not None else RelevantHadd)
    monkeypatch.setenv("NOWPLAN_PURE_PYTHON", "1")
    srch = _Search(prob.domain, prob.objects, prob.init, flat_levels(), PlannerConfig(heuristic="hadd"), None)
    assert isinstance(srch.hadd, RelevantHadd)


@pytest.mark.skipif(kernel_class() is None, reason="the compiled kernel is not built")
@pytest.mark.parametrize("domain,problem,crit", CASES)
def test_kernel_hadd_equals_the_full_exploration_along_a_walk(domain, problem, crit):
    """The kernel's values equal hadd_ids' for every fact that does not hold, and are 0 for those that do."""
    d = DATA / domain
    prob = load_pddl(d / "domain.pddl", d / f"{problem}.pddl", d / "logistics.crit" if crit else None)
    rng = random.Random(11)
    tops = sorted({flat_levels().top, prob.domain.top_level})
    compared = overridden = 0
    for s in _walk(prob, 12, rng):
        for top in tops:
            srch = _Search(prob.domain, prob.objects, s, LevelMap(top), PlannerConfig(), None)
            task = ground_task(srch.grounder, srch.drop)
            over = LevelMap(top)
            if top > flat_levels().top:
                over = LevelMap(top).next_level(rng.choice(task.acts).action)
                overridden += 1
            for levels in (LevelMap(top), over):
                srch = _Search(prob.domain, prob.objects, s, levels, PlannerConfig(), None)
                assert kernel_hadd(task, top)
                full = hadd_ids(srch.grounder, levels, srch.drop, srch.cost)
                kh = KernelHadd(task, levels, srch.true_ids())
                for f in range(len(srch.table.atoms)):
                    a = srch.table.atoms[f]
                    if a.predicate in srch.drop:
                        continue
                    if srch.fholds(f):
                        assert f >= kh.nfacts or kh.values[f] == 0.0, a
                    else:
                        assert kh.get(f) == full.get(f, math.inf), (a, levels)
                        compared += 1
    assert compared > 0 and (overridden > 0 or not crit)


def test_lmcut_cuts_kept_across_new_explorations_equal_fresh_ones():
    """The lazy relaxation keeps its LM-cut cache while only new facts are explored: same values as fresh."""
    d = DATA / "logistics"
    prob = load_pddl(d / "domain.pddl", d / "p03.pddl")
    cfg = PlannerConfig(heuristic="lmcut", lazy_relaxation=True)
    shared = _Search(prob.domain, prob.objects, prob.init, flat_levels(), cfg, None)
    acts = [ga.action for ga in ground_task(shared.grounder, shared.drop).acts]
    pool = sorted({e for a in acts for e in a.effects() if e.value is not False}, key=str)
    rng = random.Random(5)
    for _ in range(60):
        goal = frozenset(shared.table.id(a) for a in rng.sample(pool, rng.randint(1, 4)))
        fresh = _Search(prob.domain, prob.objects, prob.init, flat_levels(), cfg, None)
        assert shared.relaxed is not None and fresh.relaxed is not None
        assert shared.relaxed.estimate(goal) == fresh.relaxed.estimate(goal)
    assert shared.relaxed.cut_hits > 0
