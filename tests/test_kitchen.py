"""The PyBullet kitchen (seed 004): detection by ray casts, Inspect solved online, unreachable goals."""

from __future__ import annotations

import time

import pytest

pytest.importorskip("pybullet")

from nowplan.acting.online import OnlinePolicy  # noqa: E402
from nowplan.acting.strategy import parse_strategy  # noqa: E402
from nowplan.core.atoms import Goal, atom  # noqa: E402
from nowplan.core.domain import Problem  # noqa: E402
from nowplan.domains.kitchen import scene as S  # noqa: E402
from nowplan.domains.kitchen.tasks import make  # noqa: E402


def test_closed_drawers_hide_their_contents() -> None:
    ep = make("inspect", 0)
    w = ep.world
    seen = [w.detect()[0]["green"] is not None for _ in range(10)]
    assert not any(seen)  # in the closed bottom drawer
    w.drawers["bottom"] = S.DRAWER_OPEN
    seen = [w.detect()[0]["green"] is not None for _ in range(30)]
    assert 15 <= sum(seen) < 30 or all(seen)  # visible, missed only with p_FN


def test_inspect_with_both_succeeds_on_seeded_problem() -> None:
    ep = make("inspect", 0)
    m = OnlinePolicy(ep.problem, ep.world, ep.belief, parse_strategy("online+reuse+deferred", time_limit=60)).run()
    assert m.outcome.value == "reached", m.reason
    assert m.action_counts["detect"] >= 1 and m.action_counts["pull"] == 1 and m.action_counts["push"] == 1
    assert ep.world.frames["green"] == "bottom" and ep.world.drawers["bottom"] == 0.0
    assert ep.belief.particles["green"].frame_mass("bottom") >= 0.95


def test_unreachable_goal_ends_with_a_reason() -> None:
    ep = make("inspect", 0)
    # the tall cracker box can never be believed inside a closed top drawer and on the stove at once
    goal = Goal.of([atom("In", "cracker", "stove"), atom("In", "green", "top")])
    prob = Problem(ep.problem.domain, ep.problem.objects, ep.belief, goal)
    t0 = time.perf_counter()
    strategy = parse_strategy("online+reuse+deferred", time_limit=8, max_actions=15)
    m = OnlinePolicy(prob, ep.world, ep.belief, strategy).run()
    assert m.outcome.value in ("failed", "limit") and m.reason
    assert time.perf_counter() - t0 < 60
