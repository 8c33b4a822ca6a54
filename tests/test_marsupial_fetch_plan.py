"""The estimator's small plan for ``door(v) = p`` read off the loader's path (issue 19 target 3).

``fetch_plan`` must be the answer the estimator's regression search gives for the same atoms in
the same belief: every answer it gives during RCHPN runs is compared with the search's.
"""

from __future__ import annotations

from typing import Any

import pytest

from nowplan.acting.resources import Estimator
from nowplan.core.atoms import atom
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.domains.marsupial.fetch_plan import fetch_plan

pytestmark = pytest.mark.timeout(300)


@pytest.mark.parametrize(("regime", "n", "trial"), [("both", 6, 0), ("single", 7, 1), ("dests", 8, 0)])
def test_fetch_plans_equal_the_searchs(regime: str, n: int, trial: int) -> None:
    from nowplan.domains.marsupial.flatcmp import timed_run
    from nowplan.domains.marsupial.scenarios import episode

    orig = Estimator._support
    seen = {"answered": 0, "other": 0}

    def checked(self: Estimator, action: Action, levels: LevelMap, crit: int) -> Any:
        out = orig(self, action, levels, crit)
        unmet = self._unmet(action, crit)
        own = fetch_plan(self.domain, unmet, self.belief) if unmet else None
        if own is not None:
            searched = self.small_plan(unmet, levels)
            assert own == searched == out, f"{action}: loader path {own}, search {searched}, estimate {out}"
            seen["answered"] += 1
        elif unmet:
            seen["other"] += 1
        return out

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(Estimator, "_support", checked)
        ep = episode(regime, n, trial)
        _, _, ok = timed_run(ep, "hpn+peephole", trial, 120.0)
    assert ok and seen["answered"] > 0 and seen["other"] > 0


def test_fetch_plan_answers_only_door_atoms_of_a_package_aboard() -> None:
    from nowplan.domains.marsupial.scenarios import episode

    ep = episode("both", 4, 0)
    dom, belief = ep.problem.domain, ep.world.state
    vehicles = sorted({str(args[0]) for args in belief.facts("cargo")})
    assert vehicles
    # nothing aboard at the start: no door atom is the model's to answer, nor any other atom
    for veh in vehicles:
        assert fetch_plan(dom, [atom("door", veh, value="p0")], belief) is None
        assert fetch_plan(dom, [atom("door", veh, value="none")], belief) is None
    assert fetch_plan(dom, [atom("in", "p0", vehicles[0])], belief) is None
    assert fetch_plan(dom, [], belief) is None
