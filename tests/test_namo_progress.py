"""NAMO under the progress guard: the belief's fingerprint, the world's truth and its faults.

* ``NamoBelief.fingerprint`` identifies a situation: a real cycle (the robot back where it was,
  knowing what it knew) repeats it; progress (a look that tightens a variance, fog revealed, an
  object moved, something grasped) changes it.
* ``NamoWorld.true_state`` lets the executive judge ``reached`` in the world; ``set_faults``
  makes motions stop short, grasps miss and objects move by themselves.
* Two loops measured at sensor noise 0.1/m (seeds of domains 1 and 2) end at the goal: a look
  that cannot clear a region (the object's body is in it) and a drag planned for where an
  object was before a look moved its estimate.
"""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("shapely")

from nowplan.acting.metrics import Outcome  # noqa: E402
from nowplan.acting.progress import CycleDetector, belief_fingerprint, situation  # noqa: E402
from nowplan.acting.run import run_episode  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.core.atoms import Goal, atom  # noqa: E402
from nowplan.core.operators import Action  # noqa: E402
from nowplan.domains.namo.belief import NamoBelief  # noqa: E402
from nowplan.domains.namo.geometry import Box, Manip, MapGeometry, Pt, Region  # noqa: E402
from nowplan.domains.namo.model import PREDICATES, build_domain  # noqa: E402
from nowplan.domains.namo.scenarios import make  # noqa: E402
from nowplan.domains.namo.world import NamoWorld, TrueObject  # noqa: E402
from nowplan.experiments.faults import apply_faults, split_scenario  # noqa: E402

GEOM = MapGeometry(6.0, 4.0, ())
BOX = Box(4.0, 2.0, 0.5, 0.5)


def _belief(x: float = 1.0, y: float = 2.0) -> NamoBelief:
    b = NamoBelief(GEOM, np.array([x, y]))
    b.detect("box", BOX.cx - x, BOX.cy - y, 0.3, (BOX.w, BOX.h))  # seen from afar: sigma about 0.3
    return b


# -- the fingerprint ------------------------------------------------------------------------------
def test_the_fingerprint_is_the_protocols_and_ignores_counters_and_jitter() -> None:
    b = _belief()
    fp = belief_fingerprint(b)
    assert fp == b.fingerprint() and hash(fp) == hash(b.fingerprint())
    b.version += 7
    b.percept += 3  # a place always bumps the percept counter: no progress by itself
    b.trajectory.append(Pt(3.0, 3.0))
    b.robot_mean = b.robot_mean + np.array([0.01, -0.01])  # the jitter at the end of a move
    assert b.fingerprint() == fp


def test_progress_changes_the_fingerprint() -> None:
    b = _belief()
    seen = {b.fingerprint()}
    for noise in (0.1, 0.03, 0.01):  # looks that tighten the object's variance (each by more than FP_SIGMA)
        before = b.objects["box"].sigma
        b.detect("box", BOX.cx - 1.0, BOX.cy - 2.0, noise, (BOX.w, BOX.h))
        assert b.objects["box"].sigma < before / 1.25
        assert b.fingerprint() not in seen
        seen.add(b.fingerprint())
    b.observed[:40] = True  # fog revealed
    assert b.fingerprint() not in seen
    seen.add(b.fingerprint())
    b.held = "box"  # grasped
    assert b.fingerprint() not in seen
    b.held = None
    b.objects["box"].mean = b.objects["box"].mean + np.array([0.5, 0.0])  # moved
    assert b.fingerprint() not in seen


def test_a_looping_namo_situation_is_detected_and_ends_as_a_livelock() -> None:
    """The robot drives A -> B -> A -> ... learning nothing: the third clean cycle is a livelock."""
    b = _belief()
    d = CycleDetector(max_cycles=3)
    goals = ("RobotAt((5.0,2.0))",)
    d.start(situation(b.fingerprint(), goals))
    cycles = []
    for i in range(8):
        b.robot_mean = np.array([2.5, 2.0]) if i % 2 == 0 else np.array([1.0 + 0.02 * (i % 3), 2.0])
        cyc = d.observe(situation(b.fingerprint(), goals), succeeded=True, exogenous=False)
        if cyc is not None:
            cycles.append(cyc)
        if d.livelocked:
            break
    assert d.livelocked and len(cycles) == 3 and all(c.clean and c.length == 2 for c in cycles)


def test_a_normal_namo_run_is_not_ended_by_the_guard() -> None:
    for strategy in ("hpn", "hpn+aggressive", "hpn+selective+foresight"):
        ep = make("domain1", 0)
        m = run_episode(ep, parse_strategy(strategy), 0)
        assert m.outcome is Outcome.REACHED, (strategy, m.reason)
        assert m.goal_in_world is True and m.disagreement == ()  # judged in the world too


# -- the world: truth and faults --------------------------------------------------------------
def _move(start: Pt, end: Pt) -> Action:
    return Action(build_domain().operator_map["Move"], (start, end, Region(start, end, GEOM.robot_radius)))


def test_the_true_state_answers_the_domains_fluents() -> None:
    w = NamoWorld(GEOM, Pt(1.0, 2.0), [TrueObject("box", BOX)], seed=0)
    truth = w.true_state()
    test = PREDICATES["RobotAt"].test
    assert test is not None and test(truth, (Pt(1.1, 2.0),), True) and not test(truth, (Pt(3.0, 2.0),), True)
    assert truth.objects["box"].center == BOX.center and truth.objects["box"].sigma == 0.0
    assert truth.held is None and bool(truth.observed.all())
    dom = build_domain()
    goal = Goal.of([atom("RobotAt", Pt(1.0, 2.0))], dom.rules)
    assert dom.satisfies(truth, goal)
    w.robot = np.array([3.0, 2.0])  # the world changed; the truth follows it
    assert not dom.satisfies(w.true_state(), goal)


def test_set_faults_makes_moves_stop_short_and_grasps_miss() -> None:
    w = NamoWorld(GEOM, Pt(1.0, 1.0), [], seed=3)
    w.set_faults(failure_prob=1.0)
    obs = w.execute(_move(Pt(1.0, 1.0), Pt(3.0, 1.0)))
    assert not obs.success and obs.info["reason"] == "move stopped early"
    assert 0.3 * 2.0 - 0.06 <= obs.data["traveled"] <= 0.8 * 2.0 + 1e-9 and not obs.data["completed"]
    w.set_faults(failure_prob=0.0)
    assert w.execute(_move(w.pose, Pt(3.0, 1.0))).success  # no faults: the move completes
    with pytest.raises(ValueError, match="failure_prob must be in"):
        w.set_faults(failure_prob=1.5)


def test_an_injected_grasp_failure_misses() -> None:
    w = NamoWorld(GEOM, Pt(3.4, 2.0), [TrueObject("box", BOX)], seed=0)
    w.set_faults(failure_prob=1.0)
    w.noise = w.noise.__class__(**{**w.noise.__dict__, "move_fail": 0.0})  # only the grasp fails
    m = Manip("box", Pt(3.4, 2.0), Pt(3.4, 2.0), BOX.center, BOX.center, Pt(3.4, 2.0), (Pt(3.4, 2.0),),
              (Pt(3.4, 2.0),), (Pt(3.4, 2.0),))
    pick = Action(build_domain().operator_map["Pick"], ("box", m, m.home, m.pick_conf, None))
    obs = w.execute(pick)
    assert not obs.success and obs.info["reason"] == "the grasp slipped" and w.held is None


def test_exogenous_changes_push_objects_and_are_reported() -> None:
    w = NamoWorld(GEOM, Pt(1.0, 1.0), [TrueObject("box", BOX)], seed=1)
    w.set_faults(exogenous_prob=1.0)
    moved = []
    for _ in range(10):
        obs = w.execute(_move(w.pose, w.pose))
        moved += list(obs.exogenous)
    assert moved and all(t.startswith("box pushed from") for t in moved)
    assert w.objects["box"].center != BOX.center and w.box_hits(w.objects["box"], "box") is None


def test_the_sweeps_fault_knobs_reach_the_namo_world() -> None:
    base, faults = split_scenario("domain1?failure=0.3&exogenous=0.2")
    ep = make(base, 0)
    apply_faults(ep, faults)
    assert ep.world.noise.move_fail == 0.3 and ep.world.noise.grasp_fail == 0.3 and ep.world.exogenous_prob == 0.2


# -- loops measured at sensor noise 0.1/m -------------------------------------------------------
def test_look_clear_needs_the_objects_body_out_of_the_region_and_pick_a_fitting_manipulation() -> None:
    b = _belief()
    b.objects["box"].cov = np.eye(2) * 0.0001
    through, beside = Region(Pt(1.0, 2.0), Pt(5.0, 2.0), 0.25), Region(Pt(1.0, 3.2), Pt(5.0, 3.2), 0.25)
    out_of_way = PREDICATES["OutOfWay"].test
    assert out_of_way is not None
    assert not out_of_way(b, (through, "box"), True) and out_of_way(b, (beside, "box"), True)
    fits = PREDICATES["Fits"].test
    assert fits is not None
    here = b.objects["box"].center
    m = Manip("box", Pt(3.0, 2.0), Pt(3.4, 2.0), here, here, Pt(3.4, 2.0), (Pt(3.4, 2.0),), (Pt(3.4, 2.0),),
              (Pt(3.4, 2.0),))
    assert fits(b, ("box", m), True)
    b.objects["box"].mean = b.objects["box"].mean + np.array([0.0, 0.2])  # a look moved the estimate
    assert not fits(b, ("box", m), True)


@pytest.mark.slow
@pytest.mark.parametrize("scenario,strategy,seed", [
    ("domain2?sigma_per_m=0.1", "hpn+peephole", 0),  # looked at a box whose body is in the way, 1000 times
    ("domain3?sigma_per_m=0.1", "hpn+peephole", 1),  # the same
    ("domain1?sigma_per_m=0.1", "hpn", 4),  # dragged doorA into a wall, 500 times
])
def test_loops_at_high_sensor_noise_end_at_the_goal(scenario: str, strategy: str, seed: int) -> None:
    base, faults = split_scenario(scenario)
    ep = make(base, seed)
    apply_faults(ep, faults)
    m = run_episode(ep, parse_strategy(strategy, time_limit=120), seed)
    assert m.outcome is Outcome.REACHED, m.reason
    assert m.actions < 100


# -- the executive: a loop whose every round fails ends with its reason ----------------------------
class _DropsItBack:
    """step1 succeeds; step2 always fails and undoes step1 (a drag stopped by a wall drops the object)."""

    def __init__(self) -> None:
        from nowplan.core.state import State

        self.state = State([atom("s0")])

    def execute(self, action: Action):  # type: ignore[no-untyped-def]
        from nowplan.core.state import State
        from nowplan.worlds.base import Observation

        if action.name == "step1":
            self.state = State([atom("s0"), atom("s1")])
            return Observation(True, self.state)
        self.state = State([atom("s0")])
        return Observation(False, self.state, (), {"reason": "dropped"})


@pytest.mark.parametrize("strategy", ["hpn", "hpn+flexible", "online"])
def test_cycles_that_each_fail_end_failed_with_the_reason_not_by_the_budget(strategy: str) -> None:
    from nowplan.belief.symbolic import SymbolicBelief
    from nowplan.core.domain import Problem
    from nowplan.core.state import State
    from nowplan.domains.registry import Episode

    from test_mechanisms import CHAIN

    init = State([atom("s0")])
    prob = Problem(CHAIN, {}, init, Goal.of([atom("s3")]))
    m = run_episode(Episode(prob, _DropsItBack(), SymbolicBelief(init)), parse_strategy(strategy, max_stalls=10))
    assert m.outcome is Outcome.FAILED and m.reason.startswith("no progress: 10 cycles"), m.reason
    assert "dropped" in m.reason and m.actions <= 2 * 10 + 2


def test_failed_cycles_are_counted_until_progress() -> None:
    d = CycleDetector()
    d.start("a")
    for _ in range(3):
        d.observe("b", succeeded=True, exogenous=False)
        d.observe("a", succeeded=False, exogenous=False)
    # every return after the first step closes a cycle, and each has the failure in it
    assert d.failed_cycles == 5 and d.cycles == 0 and not d.livelocked
    d.forget(cycles=True)
    assert d.failed_cycles == 0
