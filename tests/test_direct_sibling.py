"""A refinement that swaps the refined step for a ready sibling without a planner call (acting/direct_sibling.py).

Satellite (benchmarks/classical) under its automatic hierarchy: refining ``take_image`` by an instrument
that is off on a satellite whose power another instrument holds has no short chain (switch the other off,
this one on, calibrate, then the image: four steps, one of which leaves an atom past its successor), so
the planner was called; its plan swaps in another instrument.  The direct refinement takes the sibling
that is powered and calibrated already; a sibling that is not is never taken, a learnt nogood is
respected, and a step that was itself swapped in gets no second swap.  An executive run reaches the goal
with fewer planner calls and the same cost.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from nowplan.acting.hpn import Executive
from nowplan.acting.metrics import Outcome
from nowplan.acting.refine import direct_refinement
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Problem
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.domains.registry import Episode
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.plan import Plan
from nowplan.planning.problem_hierarchy import prepare_problem
from nowplan.worlds.symbolic import SymbolicWorld

DOMAIN = Path(__file__).resolve().parents[1] / "benchmarks" / "classical" / "satellite" / "domain.pddl"

PROBLEM = """(define (problem two-sats) (:domain satellite)
  (:objects sat0 sat1 - satellite  i0 i1 i2 i3 - instrument  m n - mode  star0 star1 d0 d1 d2 - direction)
  (:init
    (on_board i0 sat0) (on_board i1 sat0) (on_board i2 sat1) (on_board i3 sat1)
    (supports i0 m) (supports i1 n) (supports i2 m) (supports i3 m)
    (calibration_target i0 star0) (calibration_target i1 star0)
    (calibration_target i2 star1) (calibration_target i3 star1)
    (power_on i1) (calibrated i1) (power_on i2) %s
    (pointing sat0 d0) (pointing sat1 d1))
  (:goal (and (have_image d2 m) (have_image d0 n))))
"""


def problem(tmp_path: Path, i2_calibrated: bool = True) -> Problem:
    path = tmp_path / "p.pddl"
    path.write_text(PROBLEM % ("(calibrated i2)" if i2_calibrated else ""))
    return prepare_problem(load_pddl(DOMAIN, path, "auto"))


def executive(prob: Problem) -> Executive:
    return Executive(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init),
                     parse_strategy("hpn+refine-flat"))


def take_image(prob: Problem, *args: str) -> Action:
    return Action(next(o for o in prob.domain.operators if o.name == "take_image"), tuple(args))


def refinement_levels(prob: Problem, step: Action) -> LevelMap:
    """The top level's map with ``step`` one class lower: its calibrated/power_on class exposed."""
    assert prob.domain.top_level == 2  # have_image; calibrated, power_on; pointing
    levels = LevelMap(prob.domain.top_level).next_level(step)
    assert levels.level(step) == 1
    return levels


def test_the_ready_sibling_is_swapped_in(tmp_path: Path) -> None:
    prob = problem(tmp_path)
    step = take_image(prob, "sat0", "d2", "i0", "m")
    levels = refinement_levels(prob, step)
    goal = Goal.of([atom("have_image", "d2", "m")])
    ex = executive(prob)
    assert direct_refinement(ex, goal, levels, step) is None  # no chain, and no swap allowed
    plan = direct_refinement(ex, goal, levels, step, may_swap=True)
    assert plan is not None
    assert [s.action.pddl() for s in plan.steps if s.action is not None] == ["(take_image sat1 d2 i2 m)"]
    assert plan.levels is levels
    assert plan.steps[-1].goal == goal
    assert ex.domain.satisfies(ex.belief, plan.preimage(0))
    # refining the sibling next exposes nothing unmet: its calibrated/power_on hold
    sibling = plan.steps[-1].action
    assert sibling is not None
    assert all(ex.domain.holds(p, ex.belief) for p in sibling.preconditions(levels.level(step)))


def test_a_sibling_that_is_not_ready_is_not_taken(tmp_path: Path) -> None:
    prob = problem(tmp_path, i2_calibrated=False)  # i2 on but not calibrated, i3 off: none ready
    step = take_image(prob, "sat0", "d2", "i0", "m")
    levels = refinement_levels(prob, step)
    goal = Goal.of([atom("have_image", "d2", "m")])
    assert direct_refinement(executive(prob), goal, levels, step, may_swap=True) is None


def test_a_learnt_nogood_is_not_swapped_in(tmp_path: Path) -> None:
    prob = problem(tmp_path)
    step = take_image(prob, "sat0", "d2", "i0", "m")
    levels = refinement_levels(prob, step)
    goal = Goal.of([atom("have_image", "d2", "m")])
    ex = executive(prob)
    ex.nogoods.learn(goal, levels, take_image(prob, "sat1", "d2", "i2", "m").key)
    assert direct_refinement(ex, goal, levels, step, may_swap=True) is None


def test_a_sibling_that_destroys_a_goal_atom_is_not_taken(tmp_path: Path) -> None:
    prob = problem(tmp_path)
    step = take_image(prob, "sat0", "d2", "i0", "m")
    levels = refinement_levels(prob, step)
    # the goal also keeps sat1 pointing at d1: a take_image of d2 by sat1 needs pointing(sat1, d2) below,
    # but at its own (abstract) level it destroys nothing, so it is still the swap; the pre-image keeps d1
    goal = Goal.of([atom("have_image", "d2", "m"), atom("pointing", "sat1", "d1")])
    plan = direct_refinement(executive(prob), goal, levels, step, may_swap=True)
    assert plan is not None
    assert atom("pointing", "sat1", "d1") in plan.preimage(0).atoms


def test_a_run_swaps_without_planner_calls_and_reaches_the_goal(tmp_path: Path, monkeypatch: Any) -> None:
    from nowplan.acting import direct_sibling

    swaps: list[Plan] = []
    made = direct_sibling.sibling_refinement

    def counted(*args: Any) -> Plan | None:
        plan = made(*args)
        if plan is not None:
            swaps.append(plan)
        return plan

    monkeypatch.setattr(direct_sibling, "sibling_refinement", counted)
    prob = problem(tmp_path)
    episode = Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), "two-sats")
    on = run_episode(episode, parse_strategy("hpn+refine-flat"), seed=0)
    assert on.outcome is Outcome.REACHED
    assert swaps  # the refinement of i0's image was the swap, made directly
    prob2 = problem(tmp_path)
    episode2 = Episode(prob2, SymbolicWorld(prob2.domain, prob2.init, seed=0), SymbolicBelief(prob2.init), "two-sats")
    off = run_episode(episode2, parse_strategy("hpn+refine-flat+nodirect"), seed=0)
    assert off.outcome is Outcome.REACHED
    assert on.execution_cost <= off.execution_cost
    assert on.plans_made <= off.plans_made
