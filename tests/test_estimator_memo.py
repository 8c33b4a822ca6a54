"""The estimator's small plans shared by steps with the same unmet preconditions (issue 19 target 3).

Every answer ``Estimator._support`` gives during RCHPN runs, from its memo by (unmet atoms, level
map) or not, equals a fresh search for that step's unmet atoms in the same belief; and the memo is
used (steps of different actions with the same unmet preconditions exist on marsupial).
"""

from __future__ import annotations

from typing import Any

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from nowplan.acting.resources import Estimator
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action

pytestmark = pytest.mark.timeout(300)


@settings(max_examples=4, deadline=None, suppress_health_check=list(HealthCheck))
@given(st.sampled_from(["both", "single"]), st.integers(3, 5), st.integers(0, 3))
def test_memoised_small_plans_equal_fresh_ones(regime: str, n: int, trial: int) -> None:
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode

    orig = Estimator._support
    seen = {"checked": 0, "shared": 0}

    def checked(self: Estimator, action: Action, levels: LevelMap, crit: int) -> Any:
        unmet = self._unmet(action, crit)
        shared = (action.key, crit) not in self._plans and (tuple(unmet), levels) in self._by_goal
        out = orig(self, action, levels, crit)
        if unmet:
            fresh = self.small_plan(unmet, levels)
            assert out == fresh, f"{action} at {crit}: memo {out} fresh {fresh}"
            seen["checked"] += 1
            seen["shared"] += shared
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Estimator, "_support", checked)
        ep = episode(regime, n, trial)
        _, _, ok = timed_run(ep, "hpn+peephole", trial, 120.0)
    assert ok and seen["checked"] > 0


def test_the_memo_is_shared_between_actions_on_a_marsupial_run() -> None:
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode

    orig = Estimator.small_plan
    asked: list[int] = []
    memo: list[int] = []

    def count(self: Estimator, unmet: Any, levels: LevelMap) -> Any:
        asked.append(1)
        return orig(self, unmet, levels)

    orig_support = Estimator._support

    def support(self: Estimator, action: Action, levels: LevelMap, crit: int) -> Any:
        before = len(asked)
        fresh_key = (action.key, crit) not in self._plans
        out = orig_support(self, action, levels, crit)
        if fresh_key and self._unmet(action, crit) and len(asked) == before:
            memo.append(1)  # answered from another action's search
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Estimator, "small_plan", count)
        mp.setattr(Estimator, "_support", support)
        ep = episode("both", 6, 0)
        _, _, ok = timed_run(ep, "hpn+peephole", 0, 120.0)
    assert ok and memo and asked


def test_peephole_trace_records_equal_fresh_ones() -> None:
    """The peephole's rewritten-plan records reuse atom texts across rewrites: same records."""
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode
    from nowplan.planning.plan import Plan

    orig = Plan.to_json
    compared: list[int] = []

    def checked(self: Plan, made: Any = None) -> Any:
        out = orig(self, made)
        if made is not None:
            assert out == orig(self)
            compared.append(1)
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Plan, "to_json", checked)
        _, _, ok = timed_run(episode("both", 5, 1), "hpn+peephole", 1, 120.0)
    assert ok and compared
