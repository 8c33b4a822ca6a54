"""Zero-cost rewrites of held facts in the regression A*: kept, but last among equal (f, h).

A subgoal's fact that holds may be regressed through a zero-cost operator into other facts that
hold (a "pure rewrite": marsupial's held ``same_city(p, v)`` into the ``at(p, l)`` it is inferred
from).  Only a plan that undoes the fact and infers it again needs the rewrite, so the search keeps
making them (``PlannerConfig.held_rewrites``) but orders the frontier by ``(f, h, r)``, ``r`` the
rewrites on the path: where the estimate is exact, the rewritten copies of a subgoal no longer
fill the plateau of equal ``f``.  A held fact's deferred successors are bounded by the node's whole
estimate where no achiever of the fact names an unmet fact (:meth:`Reach.bound`).
"""

from __future__ import annotations

from typing import Any

import pytest

from nowplan.core.atoms import Atom, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.planning.deferred import Reach
from nowplan.planning.plan import PlanStatus
from nowplan.planning.regression import PlannerConfig, plan
from tests.helpers import replay

pytestmark = pytest.mark.timeout(120)

o, a, b = Var("o"), Var("a"), Var("b")

# Objects move along next(a, b); a move needs ready(o, a), inferred at cost 0 from at(o, a) (as
# marsupial's Unload needs same_city, inferred from at).  ready(o, a) excludes at(o, c) for c != a.
OPS = (
    Operator("move", (o, a, b), (Precondition(atom("ready", o, a), 1), Precondition(atom("next", a, b), 1)),
             (atom("at", o, b), atom("at", o, a, value=False), atom("visited", o, b)), cost=1.0),
    Operator("infer", (o, a), (Precondition(atom("at", o, a), 1),), (atom("ready", o, a),), cost=0.0),
)
PREDS = {n: Predicate(n, 2) for n in ("at", "ready", "next", "visited")}


def _apart(x: Atom, y: Atom) -> bool:
    """An object is at one place, and ready only where it is."""
    if x.value is not True or y.value is not True or x.args[0] != y.args[0] or x.args[1] == y.args[1]:
        return False
    return x.predicate in ("at", "ready") and y.predicate in ("at", "ready")


DOM = Domain("toy-chain", PREDS, OPS, conflicts=(_apart,))
PLACES = ("l0", "l1", "l2")


def _problem(n: int, back: bool = False) -> tuple[dict[str, str | None], State]:
    objs = [f"o{i}" for i in range(n)]
    facts = [atom("next", "l0", "l1"), atom("next", "l1", "l2")]
    if back:
        facts += [atom("next", "l1", "l0")]
    facts += [atom("at", x, "l0") for x in objs] + [atom("ready", x, "l0") for x in objs]
    return {**{x: "obj" for x in objs}, **{p: "place" for p in PLACES}}, State(facts)


def _config(**kw: Any) -> PlannerConfig:
    return PlannerConfig(engine="regression", heuristic="lmcut", lazy_relaxation=True, serialization=False,
                         monotonic=False, **kw)


@pytest.mark.parametrize("n", [3, 6])
def test_rewrites_of_held_facts_leave_the_plateau_of_an_exact_estimate(n: int) -> None:
    """Each object: move, infer (cost 0, same f and h as its parent), move; done objects keep ready(o, l0)."""
    objects, s = _problem(n)
    goal = Goal.of([atom("at", f"o{i}", "l2") for i in range(n)])
    on = plan(DOM, objects, s, goal, LevelMap(DOM.top_level), _config())
    off = plan(DOM, objects, s, goal, LevelMap(DOM.top_level), _config(held_rewrites=False))
    assert on.status is off.status is PlanStatus.SOLVED and on.plan is not None and off.plan is not None
    assert on.plan.actions == off.plan.actions and len(on.plan) == 3 * n
    replay(DOM, s, on.plan)
    # one expansion per step: no rewritten copy of a subgoal is expanded (33 at n=6 before the ties),
    # and the held facts' deferred successors are never opened (no rewrite is even made)
    assert on.expanded == off.expanded == 3 * n
    assert on.generated == off.generated


def test_a_plan_that_undoes_a_held_fact_and_infers_it_again_is_still_found() -> None:
    """ready(o0, l0) holds and is wanted, but o0 must visit l1 first: move, infer, move back, infer."""
    objects, s = _problem(1, back=True)
    goal = Goal.of([atom("ready", "o0", "l0"), atom("visited", "o0", "l1")])
    on = plan(DOM, objects, s, goal, LevelMap(DOM.top_level), _config())
    assert on.status is PlanStatus.SOLVED and on.plan is not None
    assert [x.name for x in on.plan.actions] == ["move", "infer", "move", "infer"]
    replay(DOM, s, on.plan)
    # without the rewrites the held ready(o0, l0) blocks the move away
    off = plan(DOM, objects, s, goal, LevelMap(DOM.top_level), _config(held_rewrites=False))
    assert off.status is not PlanStatus.SOLVED


def test_reach_bound_takes_the_whole_estimate_where_no_achiever_names_an_unmet_fact() -> None:
    reach = Reach(DOM)
    T = DOM.facts
    ready = T.id(atom("ready", "o0", "l0"))  # achieved by infer(o0, l0), which names at(o0, l0) only
    other = T.id(atom("at", "o1", "l2"))
    mine = T.id(atom("at", "o0", "l0"))
    assert reach.bound(ready, [(other, 2.0)], 7.0) == (0.0, 7.0)
    assert reach.bound(ready, [(other, 2.0)]) == (0.0, 2.0)  # without the whole estimate: the dearest kept
    # an achiever names at(o0, l0): that fact may leave the child, so only the kept one's cost bounds
    assert reach.bound(ready, [(other, 2.0), (mine, 5.0)], 7.0) == (0.0, 2.0)
    assert reach.bound(ready, [], 7.0) == (0.0, 0.0)


def test_marsupial_top_level_call_expands_one_node_per_step() -> None:
    """HPN's top-level call on marsupial: rewrites of held same_city facts are made but not expanded."""
    from nowplan.belief.symbolic import SymbolicBelief
    from nowplan.domains.marsupial.model import PLANNER
    from nowplan.domains.marsupial.problems import generate

    prob, _ = generate("single", 10, 0)
    belief = SymbolicBelief(prob.init)
    cfg = PlannerConfig(**{**PLANNER.__dict__, "serialization": False, "monotonic": False})
    on = plan(prob.domain, prob.objects, belief, prob.goal, LevelMap(prob.domain.top_level), cfg)
    off = plan(prob.domain, prob.objects, belief, prob.goal, LevelMap(prob.domain.top_level),
               PlannerConfig(**{**cfg.__dict__, "held_rewrites": False}))
    assert on.status is off.status is PlanStatus.SOLVED and on.plan is not None and off.plan is not None
    assert on.plan.steps == off.plan.steps
    assert on.expanded == off.expanded == len(on.plan)
    assert on.generated == off.generated


def test_idle_steps_set_no_unmet_fact() -> None:
    from nowplan.planning.rewrites import idle, pure_rewrite
    from nowplan.planning.subgoals import NodeIndex, action_facts

    objects, s = _problem(2)
    T = DOM.facts
    holds = {T.id(x) for x in s.atoms()}
    fholds = holds.__contains__
    fs = frozenset({T.id(atom("ready", "o0", "l0")), T.id(atom("at", "o1", "l2"))})
    index = NodeIndex(T, fs)
    infer = OPS[1].instantiate({o: "o0", a: "l0"})
    move = OPS[0].instantiate({o: "o1", a: "l1", b: "l2"})
    assert idle(index, action_facts(T, infer, None, frozenset()), fholds) == 1  # re-infers a held fact
    assert idle(index, action_facts(T, move, None, frozenset()), fholds) == 0  # sets the unmet at(o1, l2)
    at0 = T.id(atom("at", "o0", "l0"))
    assert pure_rewrite(fs, (fs - {T.id(atom("ready", "o0", "l0"))}) | {at0}, fholds)
