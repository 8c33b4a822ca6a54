"""The estimator's small plans marsupial knows without a search (issue 19 target 3).

``small_plan`` (a load, a travel, or the loader's fetch path) must be the answer the estimator's
regression search gives for the same atoms in the same belief: every answer it gives during RCHPN
runs is compared with the search's.
"""

from __future__ import annotations

from collections import Counter
from typing import Any

import pytest

from nowplan.acting.resources import Estimator
from nowplan.core.atoms import atom
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.domains.marsupial.small_plans import small_plan

pytestmark = pytest.mark.timeout(300)


@pytest.mark.parametrize(("regime", "n", "trial"), [("both", 6, 0), ("single", 7, 1), ("dests", 8, 0),
                                                    ("origins", 5, 2)])
def test_small_plans_equal_the_searchs(regime: str, n: int, trial: int) -> None:
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode

    orig = Estimator._support
    answered: Counter[str] = Counter()

    def checked(self: Estimator, action: Action, levels: LevelMap, crit: int) -> Any:
        out = orig(self, action, levels, crit)
        unmet = self._unmet(action, crit)
        own = small_plan(self.domain, unmet, self.belief, levels) if unmet else None
        if own is not None:
            searched = self.small_plan(unmet, levels)
            assert own == searched == out, f"{action}: known {own}, search {searched}, estimate {out}"
            answered[unmet[0].predicate] += 1
        elif unmet:
            answered["searched"] += 1
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Estimator, "_support", checked)
        ep = episode(regime, n, trial)
        _, _, ok = timed_run(ep, "hpn+peephole", trial, 120.0)
    # each kind is met, and some small plans are still searched
    assert ok and answered["in"] and answered["at"] and answered["searched"], answered
    if regime != "origins":
        assert answered["door"], answered


def test_small_plan_answers_only_what_it_knows() -> None:
    from nowplan.domains.marsupial.scenarios import episode

    ep = episode("both", 4, 0)
    dom, belief = ep.problem.domain, ep.world.state
    levels = LevelMap(dom.top_level)
    vehicles = sorted({str(args[0]) for args in belief.facts("cargo")})
    assert vehicles
    for veh in vehicles:
        # nothing aboard at the start: no door atom, and several atoms at once, are left to the search
        assert small_plan(dom, [atom("door", veh, value="p0")], belief, levels) is None
        assert small_plan(dom, [atom("door", veh, value="none")], belief, levels) is None
        assert small_plan(dom, [atom("in", "p0", veh), atom("in", "p1", veh)], belief, levels) is None
    assert small_plan(dom, [], belief, levels) is None
    # a package lying where a vehicle goes: its load there, if that vehicle reaches it
    here = next(str(a[1]) for a in belief.facts("at") if a[0] == "p0")
    for veh in vehicles:
        out = small_plan(dom, [atom("in", "p0", veh)], belief, levels)
        if belief.value(("reachable", (here, veh))):
            assert out is not None and [a.key for a in out] == [("load", ("p0", veh, here))]
        else:
            assert out is None
