"""The forward engine: grounding, the integer task, h_FF, lazy GBFS / A*, action elimination."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.core.atoms import Atom, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import task as task_mod
from nowplan.planning import task_grounding
from nowplan.planning.forward import regress_actions, search
from nowplan.planning.hff import RelaxedHeuristic
from nowplan.planning.plan import PlanStatus
from nowplan.planning.postprocess import eliminate_actions
from nowplan.planning.regression import PlannerConfig, plan
from tests.helpers import replay

DATA = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"
CASES = [(d, p) for d in ("gripper", "logistics", "blocksworld", "lights") for p in ("p01.pddl", "p03.pddl")]


@pytest.mark.parametrize(("dom", "prob"), CASES)
@pytest.mark.parametrize("search_kind", ["gbfs", "astar"])
def test_forward_plans_replay_with_exact_preimages(dom: str, prob: str, search_kind: str) -> None:
    p = load_pddl(DATA / dom / "domain.pddl", DATA / dom / prob)
    cfg = PlannerConfig(search=search_kind, weight=1.0 if search_kind == "astar" else 2.0)  # type: ignore[arg-type]
    res = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), cfg)
    assert res.solved and res.plan is not None and res.method == f"forward:{search_kind}"
    replay(p.domain, p.init, res.plan)
    # each pre-image is the regression of the next one (the regression planner's own pre-image)
    again = regress_actions(p.domain, p.init, p.goal, list(res.plan.actions), flat_levels())
    assert again is not None and [g for _, g in again] == [s.goal for s in res.plan.steps]


@pytest.mark.parametrize(("dom", "prob"), [("gripper", "p02.pddl"), ("blocksworld", "p02.pddl"),
                                           ("logistics", "p01.pddl")])
def test_astar_with_hmax_is_optimal_on_small_problems(dom: str, prob: str) -> None:
    p = load_pddl(DATA / dom / "domain.pddl", DATA / dom / prob)
    opt = plan(p.domain, p.objects, p.init, p.goal, flat_levels(),
               PlannerConfig(search="astar", weight=1.0, forward_heuristic="max", cost_type="normal"))
    # uniform-cost search (weight 0: the heuristic is ignored) is optimal by construction
    ucs = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), PlannerConfig(search="astar", weight=0.0))
    greedy = plan(p.domain, p.objects, p.init, p.goal, flat_levels())
    assert opt.plan is not None and ucs.plan is not None and greedy.plan is not None
    assert opt.plan.cost() == ucs.plan.cost() <= greedy.plan.cost()
    assert opt.expanded < ucs.expanded  # h_max prunes


def test_the_same_call_gives_the_same_plan_whatever_the_cache_saw_before() -> None:
    p = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p03.pddl")
    task_grounding._CACHE.clear()
    first = plan(p.domain, p.objects, p.init, p.goal, flat_levels())
    # plan from a later state (the cache grows its reached set), then ask again
    assert first.plan is not None
    later = p.init.apply(first.plan.actions[0].effects())
    plan(p.domain, p.objects, later, p.goal, flat_levels())
    again = plan(p.domain, p.objects, p.init, p.goal, flat_levels())
    assert again.plan is not None and again.plan.actions == first.plan.actions


# a tiny domain with a negative precondition, a negative goal and two fluents per object
X = Var("x")
PREDS = {n: Predicate(n, 1) for n in ("on", "lit", "broken")}


def _op(name: str, pre: list[Atom], eff: list[Atom], crit: int = 1) -> Operator:
    return Operator(name, (X,), tuple(Precondition(a, crit) for a in pre), tuple(eff))


def test_negative_preconditions_and_goals_compile_into_facts() -> None:
    dom = Domain("neg", PREDS, (
        _op("switch_on", [atom("on", X, value=False), atom("broken", X, value=False)], [atom("on", X)]),
        _op("switch_off", [atom("on", X)], [atom("on", X, value=False)]),
        _op("light", [atom("on", X)], [atom("lit", X)]),
        _op("fix", [atom("broken", X)], [atom("broken", X, value=False)]),
    ))
    init = State([atom("broken", "a")])
    goal = Goal.of([atom("lit", "a"), atom("on", "a", value=False)])
    res = plan(dom, {"a": None}, init, goal, flat_levels())
    assert res.solved and res.plan is not None
    assert [a.name for a in res.plan.actions] == ["fix", "switch_on", "light", "switch_off"]
    replay(dom, init, res.plan)


def test_an_unreachable_goal_is_refused_before_searching() -> None:
    dom = Domain("neg", PREDS, (_op("light", [atom("on", X)], [atom("lit", X)]),))
    res = plan(dom, {"a": None}, State(), Goal.of([atom("lit", "a")]), flat_levels())
    assert res.status is PlanStatus.UNSOLVABLE and "lit(a)" in res.reason and res.expanded == 0


def test_hff_is_zero_at_the_goal_and_infinite_at_a_dead_end() -> None:
    p = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl")
    t = task_mod.build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: 1.0)
    h = RelaxedHeuristic(t, "ff", "one")
    h0, preferred = h.evaluate(t.init)
    assert h0 > 0 and preferred and all(all(f in t.init for f in t.pre[a]) for a in preferred)
    hadd, _ = RelaxedHeuristic(t, "add", "one").evaluate(t.init)
    hmax, _ = RelaxedHeuristic(t, "max", "one").evaluate(t.init)
    assert hmax <= h0 <= hadd
    goal_state = frozenset(t.goal)
    assert h.evaluate(goal_state | t.init)[0] == 0.0
    assert h.evaluate(frozenset())[0] == float("inf")  # no robot anywhere: nothing can move


def test_action_elimination_drops_what_nothing_needs() -> None:
    p = load_pddl(DATA / "gripper" / "domain.pddl", DATA / "gripper" / "p01.pddl")
    t = task_mod.build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: 1.0)
    res = search(t)
    assert res.actions is not None
    ids = {a: i for i, a in enumerate(t.actions)}
    good = [ids[a] for a in res.actions]
    # a detour: move to the other room and back before the plan
    moves = [i for i, a in enumerate(t.actions) if a.name == "move" and all(f in t.init for f in t.pre[i])]
    back = next(j for j, a in enumerate(t.actions)
                if a.name == "move" and a.args == tuple(reversed(t.actions[moves[0]].args)))
    padded = [moves[0], back, *good]
    assert eliminate_actions(t, padded) == eliminate_actions(t, good)
    assert len(eliminate_actions(t, padded)) <= len(good)


def test_abstract_levels_search_forward_with_conflicts_as_deletes() -> None:
    from nowplan.domains.logistics import SIZES, generate
    from nowplan.domains.logistics.model import DOMAIN as LOG

    prob = generate(SIZES["small"], 1)
    res = plan(LOG, prob.objects, prob.init, prob.goal, LevelMap(LOG.top_level), PlannerConfig(engine="forward"))
    assert res.solved and res.plan is not None and res.method == "forward:lama"
    assert all(not a.name.startswith(("drive", "fly")) for a in res.plan.actions)
    replay(LOG, prob.init, res.plan, concrete=False)


@pytest.mark.parametrize(("dom", "prob"), CASES)
def test_lama_search_and_anytime_improvement_keep_the_contract(dom: str, prob: str) -> None:
    p = load_pddl(DATA / dom / "domain.pddl", DATA / dom / prob)
    first = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), PlannerConfig(search="lama"))
    better = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), PlannerConfig(search="lama", improve=2.0))
    assert first.plan is not None and better.plan is not None
    assert better.plan.cost() <= first.plan.cost()  # improvement never makes a plan costlier
    replay(p.domain, p.init, better.plan)


def test_landmarks_of_a_chain_are_every_fact_on_it() -> None:
    from nowplan.planning.landmarks import LandmarkCount

    dom = Domain("chain", {n: Predicate(n, 1) for n in ("a", "b", "c", "d")}, (
        _op("ab", [atom("a", X)], [atom("b", X)]),
        _op("bc", [atom("b", X)], [atom("c", X)]),
        _op("bd", [atom("b", X)], [atom("d", X)]),
        _op("cd", [atom("c", X)], [atom("d", X)]),
    ))
    init = State([atom("a", "k")])
    t = task_mod.build_task(dom, {"k": None}, init, Goal.of([atom("d", "k")]), flat_levels(), lambda a: 1.0)
    lc = LandmarkCount(t)
    names = {str(t.facts[f]) for f in lc.landmarks}
    assert names == {"b(k)", "d(k)"}  # c(k) is avoidable (b -> d directly); a is static
    acc = lc.initial_accepted()
    h, preferred = lc.evaluate(t.init, acc)
    assert h == 2 and [t.actions[a].name for a in preferred] == ["ab"]


def test_a_landmark_left_behind_is_not_required_again() -> None:
    """Picking a package up accepts a landmark and leaves its first place: the count must fall.

    ``at_a(k)`` comes before ``at_b(k)`` (a natural ordering), but no achiever of
    ``at_b(k)`` needs it; only ``held(k)``, needed by every achiever, is ordered
    necessarily before it.
    """
    from nowplan.planning.forward import _apply
    from nowplan.planning.landmarks import LandmarkCount

    dom = Domain("carry", {n: Predicate(n, 1) for n in ("at_a", "held", "at_b")}, (
        _op("pick", [atom("at_a", X)], [atom("held", X), atom("at_a", X, value=False)]),
        _op("drop", [atom("held", X)], [atom("at_b", X), atom("held", X, value=False)]),
    ))
    t = task_mod.build_task(dom, {"k": None}, State([atom("at_a", "k")]), Goal.of([atom("at_b", "k")]),
                            flat_levels(), lambda a: 1.0)
    lc = LandmarkCount(t)
    fact = {str(f): i for i, f in enumerate(t.facts)}
    index = {next(iter(d)): i for i, d in enumerate(lc.sets)}
    assert lc.before == {index[fact["at_a(k)"]]: [index[fact["held(k)"]]],
                         index[fact["held(k)"]]: [index[fact["at_b(k)"]]]}
    acc0 = lc.initial_accepted()
    h0, _ = lc.evaluate(t.init, acc0)
    pick = next(i for i, a in enumerate(t.actions) if a.name == "pick")
    s1 = _apply(t, t.init, pick)
    h1, preferred = lc.evaluate(s1, lc.accept(acc0, s1))
    assert (h0, h1) == (2, 1)
    assert [t.actions[a].name for a in preferred] == ["drop"]


def test_forward_max_nodes_is_the_forward_search_budget() -> None:
    """``forward_max_nodes`` bounds the forward search (``nowplan plan`` sets it far above the regression
    search's ``max_nodes``, so that its time limit ends a long forward search); None: ``max_nodes``."""
    p = load_pddl(DATA / "logistics" / "domain.pddl", DATA / "logistics" / "p03.pddl")
    tight = plan(p.domain, p.objects, p.init, p.goal, flat_levels(), PlannerConfig(engine="forward", max_nodes=2))
    assert tight.status is PlanStatus.NODE_LIMIT
    roomy = plan(p.domain, p.objects, p.init, p.goal, flat_levels(),
                 PlannerConfig(engine="forward", max_nodes=2, forward_max_nodes=100_000))
    assert roomy.solved and roomy.plan is not None
    replay(p.domain, p.init, roomy.plan)
    capped = plan(p.domain, p.objects, p.init, p.goal, flat_levels(),
                  PlannerConfig(engine="forward", max_nodes=100_000, forward_max_nodes=2))
    assert capped.status is PlanStatus.NODE_LIMIT
