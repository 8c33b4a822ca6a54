"""Issue 14: NAMO fault-benchmark failures at bbc8ff6 and the regressions of wip-namo2's first fix.

* the belief said RobotAt when the mean was inside the tolerance but the uncertainty was not
  (``NamoBelief.surely_at``);
* a Pick stopped by another object's contact was issued again and again (``blocked_picks``);
* the move generator's request bound starved searches planning the whole problem, and a bigger
  bound lost others among moves (two passes, nowplan.acting.whole); a refinement whose move
  generator gave up searched on without moves until its time limit (GivesUp).
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.core.operators import Action  # noqa: E402
from nowplan.domains.namo.belief import LOOP_LIMIT, NamoBelief  # noqa: E402
from nowplan.domains.namo.estimate import ObjectEstimate  # noqa: E402
from nowplan.belief.protocols import GivesUp  # noqa: E402
from nowplan.domains.namo.generators import UNRESTRICTED_LIMIT, move_request_bound  # noqa: E402
from nowplan.domains.namo.geometry import Manip, MapGeometry, Pt  # noqa: E402
from nowplan.domains.namo.model import PREDICATES, build_domain  # noqa: E402
from nowplan.planning.context import PlanningContext  # noqa: E402
from nowplan.worlds.base import Observation  # noqa: E402


def _belief(mean: tuple[float, float], sym: Pt | None, sigma: float) -> NamoBelief:
    geom = MapGeometry(6.0, 4.0, ())
    b = NamoBelief(geom, np.array(mean), robot_sym=sym)
    b.robot_var = sigma**2
    return b


def test_robot_at_away_from_the_nominal_pose_needs_confidence() -> None:
    # a move towards (3.1, 2.1) stopped 0.14 m short: the mean is inside at_tol (0.15), the truth
    # (sigma 0.024) may well be outside it; RobotAt must not say "arrived"
    b = _belief((2.96, 2.1), None, 0.024)
    goal = Pt(3.1, 2.1)
    assert b.at(goal)  # the plain mean test would say arrived
    assert b.nominal() != goal
    assert not b.surely_at(goal)
    assert b.surely_at(b.nominal())  # where the planner starts from still holds
    b.robot_var = 0.0  # the world's true state: no variance, the tests agree
    assert b.surely_at(goal) == b.at(goal)
    near = _belief((3.08, 2.1), Pt(3.1, 2.1), 0.024)  # a completed move: the commanded end is nominal
    assert near.surely_at(Pt(3.1, 2.1))


def _estimate(name: str, at: tuple[float, float]) -> ObjectEstimate:
    return ObjectEstimate(name, np.array(at), np.eye(2) * 0.02**2, (0.5, 0.5), 0)


def test_a_pick_stopped_by_another_object_no_longer_fits() -> None:
    b = _belief((1.0, 2.0), Pt(1.0, 2.0), 0.01)
    b.objects["door"] = _estimate("door", (3.0, 2.0))
    b.objects["box"] = _estimate("box", (2.0, 2.4))
    m = Manip("door", Pt(1.0, 2.0), Pt(2.5, 2.0), Pt(3.0, 2.0), Pt(3.0, 3.0), Pt(2.5, 3.0),
              (Pt(1.0, 2.0), Pt(2.5, 2.0)), (Pt(2.5, 2.0), Pt(2.5, 3.0)), (Pt(2.5, 3.0), Pt(1.0, 2.0)))
    fits = PREDICATES["Fits"].test
    assert fits is not None and fits(b, ("door", m), True)
    op = next(o for o in build_domain().operators if o.name == "Pick")
    pick = Action(op, ("door", m, m.home, m.pick_conf, None))
    # a grasp that slipped teaches nothing about the path: the manipulation still fits
    b.update(pick, Observation(False, {"traveled": 1.5, "grasped": False, "returned": True}, (), {}))
    assert fits(b, ("door", m), True) and not b.blocked_picks
    # stopped on its way by the box: the same pick would be stopped again
    contact = [("box", 0.9, 0.35, 0.05, 0.5, 0.5)]
    b.update(pick, Observation(False, {"traveled": 0.0, "grasped": False, "contacts": contact}, (), {}))
    assert b.blocked_picks == {m: "box"}
    assert fits(b, ("door", m), False)
    # the situation changed (the progress guard sees the failure taught something)
    assert ("door" in str(b.fingerprint())) and m in b.fingerprint()[-1]


def test_the_move_request_bound_of_a_refinement_and_of_a_whole_problem_search() -> None:
    refinement = PlanningContext((), {"foresight": True})
    wide = PlanningContext((), {"whole_problem": True})
    narrow = PlanningContext((), {"whole_problem": True, "restricted": True})
    assert move_request_bound(None) == move_request_bound(refinement) == move_request_bound(narrow) == LOOP_LIMIT
    assert move_request_bound(wide) == UNRESTRICTED_LIMIT > 50_000  # past any node budget: never starved
    b = _belief((1.0, 2.0), Pt(1.0, 2.0), 0.01)
    assert not any(b.planning_loop(wide, move_request_bound(wide)) for _ in range(2 * LOOP_LIMIT))
    assert b.planning_gave_up(wide) is None
    assert not any(b.planning_loop(refinement) for _ in range(LOOP_LIMIT - 1))
    assert b.planning_gave_up(refinement) is None
    assert b.planning_loop(refinement)  # a refinement's generator gives up ...
    why = b.planning_gave_up(refinement)  # ... and its search ends: the level above plans again
    assert why is not None and "1500 move requests" in why
    assert not any(b.planning_loop(narrow) for _ in range(LOOP_LIMIT - 1)) and b.planning_loop(narrow)
    assert b.planning_gave_up(narrow) is None  # a restricted whole-problem pass searches on without moves
    assert isinstance(b, GivesUp)
    # ... but says afterwards that its generator gave up (its exhausted space is then no proof)
    assert "1500 move requests" in (b.generators_gave_up(narrow) or "")
    assert b.generators_gave_up(wide) is None


def _run(scenario: str, strategy: str, seed: int) -> dict[str, object]:
    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import apply_faults, split_scenario

    base, faults = split_scenario(scenario)
    spec = get_domain("namo")
    episode = spec.scenario(base)(seed)
    apply_faults(episode, faults)
    return run_episode(episode, parse_strategy(strategy, base_planner=spec.planner, time_limit=60.0), seed).to_dict()


def test_failed_moves_near_the_goal_do_not_end_the_run_in_belief_only() -> None:
    # before: 'failed', the goal held in the belief (0.14 m from it) but not in the world
    m = _run("domain1?failure=0.5", "hpn+flexible", 10)
    assert m["outcome"] == "reached", m["reason"]
    assert not m["disagreement"]


def test_a_pick_stopped_by_an_object_is_planned_again_not_repeated() -> None:
    # before (with surely_at): 'stalled: (Pick doorA ...) failed 25 times in a row (pick path blocked by left1)'
    m = _run("domain1?exogenous=0.1", "hpn+peephole", 15)
    assert m["outcome"] == "reached", m["reason"]
    assert m["failed_actions"] <= 2


@pytest.mark.slow
def test_a_flat_search_is_not_starved_of_moves() -> None:
    # before: 'no plan for the goal (node_limit: expanded 50000 nodes without a plan)'
    m = _run("domain1?sigma_per_m=0.1", "flat", 16)
    assert m["outcome"] == "reached", m["reason"]


@pytest.mark.slow
@pytest.mark.parametrize(("scenario", "seed"), [("domain1?sigma_per_m=0.1", 4), ("domain1?sigma_per_m=0.1", 16),
                                                ("domain1?sigma_per_m=0.08", 5)])
def test_online_replanning_finds_a_plan_with_or_without_restricted_moves(scenario: str, seed: int) -> None:
    # sigma 0.1 seed 16 before: starved of moves, no plan; seed 4 and sigma 0.08 seed 5 with moves never
    # restricted: 50,000 nodes without a plan (the restricted pass finds one)
    m = _run(scenario, "online", seed)
    assert m["outcome"] == "reached", m["reason"]


@pytest.mark.slow
def test_a_refinement_whose_move_generator_gives_up_ends() -> None:
    # before: one refinement searched on without moves for 45,000 nodes and the run hit its 60 s limit
    m = _run("domain1?sigma_per_m=0.1", "hpn+noshortcuts", 6)
    assert m["outcome"] == "reached", m["reason"]
