"""A refinement that swaps the refined step for a sibling ready at the refined level, without a planner call.

When HPN refines an abstract step ω (its level lowered by one class: ``NextLevel``) and no short
chain ending in ω supplies what ω now exposes (acting/refine.py ``direct_refinement``), the
planner is called, and its plan is often one step: a *sibling* ω' (another instance of ω's
operator) that adds what ω was for and, being still at the abstract level, exposes nothing.
Satellite under ``--criticality auto``: refining ``take_image`` of an instrument that is off on a
satellite whose power another instrument holds, the planner answers with ``take_image`` by
another satellite's instrument (24 of satellite-8-50's 26 planner calls, ~7 ms each).

:func:`sibling_refinement` makes that plan directly, and picks the sibling better than the
planner's arbitrary one: ω' must add every atom of the goal that ω adds, its preconditions at
ω's *refined* level must hold now (so refining ω' in turn exposes nothing unmet: an instrument
already powered and calibrated), its pre-image of the goal at its own level must hold now (it
destroys no atom the goal keeps), and it is not a step learnt not to start a plan for this goal
(acting/backtrack.py).  Of those, the cheapest (then the first by name).  The swap is what the
planner's plan would be (one step, the sibling at its own level, the map unchanged), so the
executive's rule for swaps applies unchanged: the caller offers it only where the refined step
was not itself swapped in (:func:`nowplan.acting.refine.refine_without_swaps`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.plan import Plan, PlanStep

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive
    from nowplan.acting.refine import AtomAchievers


def sibling_refinement(ex: Executive, index: AtomAchievers, goal: Goal, levels: LevelMap, refined: Action,
                       forbidden: frozenset[Any], holds: Any, drop: frozenset[str]) -> Plan | None:
    """The one-step plan ``[ω']`` for ``goal`` with ω' a sibling of ``refined`` (see the module); None
    when ``refined`` adds no atom of ``goal`` or no sibling qualifies."""
    from nowplan.planning.preimage import preimage

    effects = {e.key: e for e in refined.effects()}
    serves: list[Atom] = [a for a in goal.atoms if (e := effects.get(a.key)) is not None and e == a]
    if not serves:
        return None
    name = refined.operator.name
    exposed = levels.level(refined)  # the refined (lowered) level: what ω' must not expose
    best: tuple[float, str, Action, Goal] | None = None
    for a in index.of(min(serves, key=lambda u: len(index.of(u)))):
        if a.operator.name != name or a.key == refined.key or a.key in forbidden:
            continue
        mine = {e.key: e for e in a.effects()}
        if any(mine.get(u.key) != u for u in serves):
            continue
        if not all(holds(p) for p in a.preconditions(exposed)):
            continue
        g0 = preimage(goal, a, levels.level(a), ex.domain, drop)
        if g0 is None or not all(holds(p) for p in g0.atoms):
            continue
        key = (a.cost(ex.belief), a.pddl())
        if best is None or key < best[:2]:
            best = (*key, a, g0)
    if best is None:
        return None
    return Plan((PlanStep(None, best[3]), PlanStep(best[2], goal)), levels)
