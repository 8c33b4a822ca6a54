"""The kitchen under the progress guard: its truth (goal judged in the world), its faults, its fingerprint."""

from __future__ import annotations

import pytest

pytest.importorskip("pybullet")

from nowplan.acting.progress import belief_fingerprint  # noqa: E402
from nowplan.core.operators import Action  # noqa: E402
from nowplan.domains.kitchen import scene as S  # noqa: E402
from nowplan.domains.kitchen.tasks import make  # noqa: E402
from nowplan.worlds.base import FaultInjection, Inspectable, Observation  # noqa: E402


def test_the_goal_is_judged_on_the_kitchens_truth() -> None:
    # Inspect: the block truly is in the closed bottom drawer (the goal), the agent does not know it
    ep = make("inspect", 0)
    dom, goal = ep.problem.domain, ep.problem.goal
    assert isinstance(ep.world, Inspectable)
    assert dom.satisfies(ep.world.true_state(), goal) and not dom.satisfies(ep.belief, goal)
    # Swap: the block truly is in the top drawer
    swap = make("swap", 0)
    assert not swap.problem.domain.satisfies(swap.world.true_state(), swap.problem.goal)


def test_injected_failures_do_nothing_and_exogenous_changes_are_refused() -> None:
    ep = make("inspect", 0)
    w = ep.world
    assert isinstance(w, FaultInjection)
    with pytest.raises(ValueError, match="no exogenous changes"):
        w.set_faults(exogenous_prob=0.5)
    pull = next(o for o in ep.problem.domain.operators if o.name == "pull")
    action = Action(pull, ("bottom",) + (None,) * (len(pull.params) - 1))
    w.set_faults(failure_prob=1.0)
    obs = w.execute(action)
    assert not obs.success and obs.info["reason"] == "injected failure" and w.drawers["bottom"] == 0.0
    w.set_faults(failure_prob=0.0)
    assert w.execute(action).success and w.drawers["bottom"] == S.DRAWER_OPEN


def test_the_fingerprint_changes_with_what_the_agent_learns() -> None:
    ep = make("inspect", 0)
    b = ep.belief
    fp = belief_fingerprint(b)
    assert fp is not None and fp == b.fingerprint()
    pull = next(o for o in ep.problem.domain.operators if o.name == "pull")
    action = Action(pull, ("bottom",) + (None,) * (len(pull.params) - 1))
    b.update(action, Observation(True, None, (), {"drawers": {"top": 0.0, "bottom": S.DRAWER_OPEN}}))
    assert b.fingerprint() != fp  # the drawer is open
    again = b.fingerprint()
    b.update(action, Observation(True, None, (), {"drawers": {"top": 0.0, "bottom": S.DRAWER_OPEN}}))
    assert b.fingerprint() == again  # nothing new
