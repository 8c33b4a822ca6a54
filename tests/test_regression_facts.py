"""The regression search over fact ids computes what the Goal-level functions compute."""

from __future__ import annotations

import random

import pytest

from nowplan.core.atoms import AtMostOne, Goal, ToleranceRule, Var, atom, conjoin, contradiction
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Operator, Precondition
from nowplan.planning.regression import preimage
from nowplan.planning.subgoals import NodeIndex, action_facts, regress

x, y, t = Var("x"), Var("y"), Var("t")


def _plain(a, b):
    """A pairwise rule without group keys: ``red(x)`` excludes ``blue(x)``."""
    return a.predicate == "red" and b.predicate == "blue" and a.args == b.args and a.value and b.value


def _toy_domain() -> Domain:
    preds = {
        "at": Predicate("at", 2), "in": Predicate("in", 2), "red": Predicate("red", 1),
        "blue": Predicate("blue", 1), "tol": Predicate("tol", 1, rule=ToleranceRule(), boolean=False),
        "free": Predicate("free", 1),
    }
    ops = (
        Operator("move", (x, y, t), (Precondition(atom("at", x, t), 2), Precondition(atom("free", y), 1)),
                 (atom("at", x, y), atom("at", x, t, value=False), atom("free", t), atom("free", y, value=False))),
        Operator("grab", (x, y), (Precondition(atom("at", x, y), 2), Precondition(atom("tol", x, value=0.5), 1)),
                 (atom("in", x, "h"), atom("at", x, y, value=False))),
        Operator("paint", (x,), (Precondition(atom("blue", x, value=False), 1), Precondition(atom("tol", x, value=0.2), 2)),
                 (atom("red", x),)),
        Operator("wash", (x,), (Precondition(atom("tol", x, value=0.1), 1),), (atom("blue", x), atom("red", x, value=False))),
        Operator("measure", (x,), (), (atom("tol", x, value=0.05),)),
    )
    return Domain("toy", preds, ops, conflicts=(AtMostOne(("at", "in")), _plain))


def _check_against_goal_preimage(domain: Domain, actions, atoms, rng: random.Random, trials: int, levels) -> int:
    """Random consistent subgoals: ``regress`` on fact ids equals ``preimage`` on Goals. Returns checks made."""
    table = domain.facts
    rules = domain.rules
    checked = 0
    for _ in range(trials):
        g = conjoin(Goal(), rng.sample(atoms, rng.randint(1, min(6, len(atoms)))), rules)
        if g is None or contradiction(list(g.atoms), rules) is not None:
            continue
        fs = table.ids_of(g.atoms)
        assert table.consistent(fs)
        node = NodeIndex(table, fs)
        for act in rng.sample(actions, min(12, len(actions))):
            for level in levels:
                want = preimage(g, act, level, domain)
                got = regress(table, node, action_facts(table, act, level, frozenset()))
                assert (want is None) == (got is None), (g, act, level, want, got)
                if want is not None:
                    assert table.goal(got) == want
                checked += 1
    return checked


def test_one_mutex_pass_on_fact_ids_finds_what_the_two_goal_passes_find():
    dom = _toy_domain()
    objs = ["a", "b", "c"]
    acts = []
    for op in dom.operators:
        names = [v for v in op.params]
        import itertools

        for combo in itertools.product(objs, repeat=len(names)):
            acts.append(op.instantiate(dict(zip(names, combo))))
    atoms = sorted({p for a in acts for p in a.preconditions()} | {e for a in acts for e in a.effects()})
    atoms += [atom("tol", o, value=v) for o in objs for v in (0.3, 0.01)]
    n = _check_against_goal_preimage(dom, acts, atoms, random.Random(1), 400, (None, 0, 1))
    assert n > 2000


def test_fact_preimages_on_marsupial_and_pddl_mutexes():
    from pathlib import Path

    from nowplan.domains.marsupial.scenarios import episode
    from nowplan.io.pddl_read import load_pddl
    from nowplan.planning.grounding import Grounder

    ep = episode("single", 3, 0)
    dom, belief = ep.problem.domain, ep.belief
    g = Grounder(dom, ep.problem.objects, belief)
    goal = ep.problem.goal
    acts, frontier = [], list(goal.atoms)
    seen = set(frontier)
    while frontier and len(acts) < 300:  # achievers of the goal and of their preconditions
        a = frontier.pop(0)
        for act in g.achievers(a, goal):
            acts.append(act)
            for p in act.preconditions():
                if p not in seen:
                    seen.add(p)
                    frontier.append(p)
    atoms = sorted(seen, key=str)
    assert _check_against_goal_preimage(dom, acts, atoms, random.Random(2), 300, (4, 3, 2, 1)) > 1000

    data = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl" / "logistics"
    prob = load_pddl(data / "domain.pddl", data / "p01.pddl") if (data / "p01.pddl").exists() else None
    if prob is None:
        pytest.skip("no logistics p01")
    g = Grounder(prob.domain, prob.objects, prob.init)
    acts = [op.instantiate(b) for op in prob.domain.operators for b in g._fill(op, {})]
    atoms = sorted({p for a in acts for p in a.preconditions()} | {e for a in acts for e in a.effects()}, key=str)
    assert _check_against_goal_preimage(prob.domain, acts, atoms, random.Random(3), 300, (None,)) > 1000


def test_generator_memo_grounds_the_same_achievers():
    """Achievers kept per (atom, what the generators read of the goal) equal those made afresh."""
    from nowplan.domains.marsupial.scenarios import episode
    from nowplan.planning.grounding import Grounder

    ep = episode("single", 3, 1)
    dom, belief = ep.problem.domain, ep.belief
    memo = Grounder(dom, ep.problem.objects, belief)
    rng = random.Random(4)
    goal = ep.problem.goal
    pool = list(goal.atoms)
    goals = [goal]
    for _ in range(60):  # subgoals made of achievers' preconditions
        a = rng.choice(pool)
        for act in memo.achievers(a, rng.choice(goals)):
            pool.extend(act.preconditions(rng.choice([None, 1, 2, 3, 4])))
        g = conjoin(Goal(), rng.sample(pool, min(len(pool), rng.randint(1, 6))), dom.rules)
        if g is not None:
            goals.append(g)
    checks = 0
    for g in goals:
        for a in g.atoms:
            fresh = Grounder(dom, ep.problem.objects, belief)
            fresh.memo = False
            assert [x.key for x in memo.achievers(a, g)] == [x.key for x in fresh.achievers(a, g)]
            assert [x.key for x in memo.achievers(a, lambda g=g: g)] == [x.key for x in fresh.achievers(a, g)]
            checks += 1
    assert checks > 50


def test_a_contradictory_root_goal_is_regressed_like_goals_are():
    """Only a root can be contradictory: its successors come from the Goal-level pre-image."""
    from nowplan.core.state import State
    from nowplan.planning.regression import PlannerConfig, plan

    dom = _toy_domain()
    init = State([atom("at", "a", "b"), atom("free", "c"), atom("tol", "a", value=0.5)])
    # at(a, b) and in(a, h) cannot both hold: the goal is contradictory (made without conjoin)
    bad = Goal(frozenset({atom("at", "a", "b"), atom("in", "a", "h")}))
    res = plan(dom, {"a": None, "b": None, "c": None, "h": None}, init, bad, LevelMap(-1),
               PlannerConfig(serialization=False, monotonic=False, max_nodes=200))
    assert not res.solved
