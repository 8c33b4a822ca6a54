"""Goal atoms an abstract plan leaves alone are owed only at its end (acting/postpone.py).

A courier on a line of rooms ``home - r1 - r2`` processes two ready items and must end at home.  Where
the robot is has criticality 1, so the top plan ``[process a, process b]`` does not see it: with
the seed's exactly regressed pre-images (``maintain``) ``robot_at(home)`` is in every one, and the
refinement of ``process a`` drives home again before ``process b`` starts.
"""

from __future__ import annotations

from nowplan.acting.postpone import postpone, postponable
from nowplan.api import (
    Domain, Episode, Goal, Operator, Outcome, Precondition, Predicate, Problem, State, SymbolicBelief,
    SymbolicWorld, Trace, Var, atom, exactly_one, parse_strategy, run_episode, static,
)
from nowplan.core.levels import LevelMap
from nowplan.planning.plan import Plan, PlanStep

r, r2, x = Var("r"), Var("r2"), Var("x")
PREDS = {p.name: p for p in (
    Predicate("robot_at", 1), Predicate("item_in", 2), Predicate("processed", 1), Predicate("link", 2),
    Predicate("lamp_on", 1), Predicate("ready", 1),
)}
OPS = (
    Operator("move", (r, r2), (Precondition(atom("robot_at", r), 1), static(atom("link", r, r2))),
             (atom("robot_at", r2), atom("robot_at", r, value=False))),
    Operator("process", (x, r), (Precondition(atom("ready", x), 2), static(atom("item_in", x, r)),
                                 Precondition(atom("robot_at", r), 1)),
             (atom("processed", x),)),
    Operator("switch", (r,), (Precondition(atom("robot_at", r), 3),), (atom("lamp_on", r, value=False),)),
)
DOMAIN = Domain("courier", PREDS, OPS[:2], conflicts=(exactly_one("robot_at", key=()),))
# with switch, an operator keeps robot_at at criticality 3: the top level (2) plans with it
SEEING = Domain("courier", PREDS, OPS, conflicts=(exactly_one("robot_at", key=()),))
LINKS = [atom("link", a, b) for a, b in (("home", "r1"), ("r1", "r2"))]
LINKS += [atom("link", b, a) for a, b in (("home", "r1"), ("r1", "r2"))]
INIT = State([atom("robot_at", "home"), atom("item_in", "a", "r2"), atom("item_in", "b", "r1"),
              atom("ready", "a"), atom("ready", "b"), *LINKS])
GOAL = Goal.of([atom("processed", "a"), atom("processed", "b"), atom("robot_at", "home")])
OBJECTS = {"home": None, "r1": None, "r2": None, "a": None, "b": None}


def _plan(actions: list[object], goal: Goal = GOAL) -> Plan:
    """The top plan of ``actions`` with every pre-image holding the goal's untouched atoms (as regressed)."""
    keep = Goal(frozenset(a for a in goal.atoms if a.predicate == "robot_at"))
    steps = [PlanStep(None, keep)] + [PlanStep(a, keep) for a in actions[:-1]] + [PlanStep(actions[-1], goal)]  # type: ignore[arg-type]
    return Plan(tuple(steps), LevelMap(DOMAIN.top_level))


def _process(item: str, room: str) -> object:
    return OPS[1].instantiate({x: item, r: room})


def test_the_parking_atom_is_owed_only_at_the_end() -> None:
    p = _plan([_process("a", "r2"), _process("b", "r1")])
    later = postponable(p, DOMAIN, INIT, GOAL)
    assert later == {atom("robot_at", "home")}
    out, got = postpone(p, DOMAIN, INIT, GOAL)
    assert got == later
    assert all(atom("robot_at", "home") not in s.goal.atoms for s in out.steps[:-1])
    assert out.goal == p.goal and out.actions == p.actions


def test_what_the_plan_touches_sees_or_does_not_hold_is_kept() -> None:
    move = OPS[0].instantiate({r: "home", r2: "r1"})
    assert postponable(_plan([_process("a", "r2"), move]), DOMAIN, INIT, GOAL) == frozenset()  # a step moves it
    elsewhere = State([atom("robot_at", "r1"), atom("ready", "a"), atom("ready", "b"), *LINKS])
    assert postponable(_plan([_process("a", "r2"), _process("b", "r1")]), DOMAIN, elsewhere, GOAL) == frozenset()
    # the top level plans with robot_at in SEEING (switch keeps it there): maintained, though these
    # two steps leave it alone
    seen = Plan(_plan([_process("a", "r2"), _process("b", "r1")]).steps, LevelMap(SEEING.top_level))
    assert not seen.is_primitive(1)
    assert postponable(seen, SEEING, INIT, GOAL) == frozenset()
    # only the problem's goal is owed later: a subgoal an abstract plan set stays maintained
    assert postponable(_plan([_process("a", "r2"), _process("b", "r1")]), DOMAIN, INIT,
                       Goal.of([atom("processed", "a"), atom("processed", "b")])) == frozenset()


def test_short_and_primitive_plans_are_left_alone() -> None:
    assert postponable(_plan([_process("b", "r1")]), DOMAIN, INIT, GOAL) == frozenset()  # one step: planned in full
    move = OPS[0].instantiate({r: "home", r2: "r1"})
    back = OPS[0].instantiate({r: "r1", r2: "home"})
    prim = Plan((PlanStep(None, Goal()), PlanStep(move, Goal()), PlanStep(back, GOAL)), LevelMap(0))
    assert postponable(prim, DOMAIN, INIT, GOAL) == frozenset()


def _run(strategy: str) -> tuple[object, Trace]:
    problem = Problem(DOMAIN, OBJECTS, INIT, GOAL)
    tr = Trace()
    ep = Episode(problem, SymbolicWorld(DOMAIN, INIT), SymbolicBelief(INIT))
    return run_episode(ep, parse_strategy(strategy), seed=0, trace=tr), tr


def test_hpn_drives_home_once() -> None:
    m, tr = _run("hpn")
    seed, _ = _run("hpn+maintain")
    assert m.outcome is Outcome.REACHED and seed.outcome is Outcome.REACHED  # type: ignore[attr-defined]
    homes = [e["action"] for e in tr.events if e["event"] == "action" and e["action"].endswith("home)")]
    assert homes == ["(move r1 home)"]  # once, at the end
    assert m.actions == 6 and seed.actions == 8  # type: ignore[attr-defined]
    assert any(e.get("postponed") == ["robot_at(home)"] for e in tr.events if e["event"] == "plan")
