"""A goal-distance estimate for regression in the kitchen (the planner's ``heuristic`` hook).

The generic fallback counts unmet atoms, which cannot tell a subgoal that
needs one move from one that needs a drawer emptied.  This estimate adds,
for every unmet atom of a subgoal, the number of actions that typically
achieve it from the current belief (moves included), in the spirit of
``h_add`` over a relaxation in which every continuous value is reachable —
what PDDLStream's optimistic stream outputs give Fast Downward's heuristics.
It is not admissible; the kitchen searches greedily with it (see
:mod:`nowplan.domains.kitchen.repro`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.domains.kitchen import scene as S

MOVE_ACT = 2.0  # a move then the action itself


def _unlocalized(belief: Any, o: str) -> float:
    """One detection if the belief does not already pin ``o`` down near its mode."""
    if belief.held == o:
        return 0.0
    return 0.0 if bool(belief.localized_at(o, belief.mode_pose(o))) else 1.0


def _tall_inside(belief: Any, d: str) -> int:
    return sum(1 for o in S.TALL if o in belief.particles and belief.particles[o].frame_mass(d) >= 0.05)


def _frame_of(belief: Any, o: str) -> str:
    return "hand" if belief.held == o else str(belief.mode_pose(o).frame)


def _open_cost(belief: Any, f: str) -> float:
    """Pulling a closed drawer (0 for the counter, the stove or an open drawer)."""
    return MOVE_ACT if f in belief.drawers and belief.drawers[f] < 0.2 else 0.0


def _pick_cost(belief: Any, o: str) -> float:
    if belief.held == o:
        return 0.0
    return MOVE_ACT + _unlocalized(belief, o) + _open_cost(belief, _frame_of(belief, o))


def atom_estimate(a: Atom, belief: Any) -> float:
    """Actions needed for one unmet atom, from the current belief (a rough additive estimate)."""
    name, args = a.predicate, tuple(str(x) for x in a.args)
    if name == "AtConf":
        return 1.0
    if name == "Open":
        if args[0] not in belief.drawers:
            return 0.0
        return MOVE_ACT if a.value is True else MOVE_ACT + 2 * MOVE_ACT * _tall_inside(belief, args[0])
    if name in ("HandEmpty", "StoveOn"):
        return MOVE_ACT
    if name == "Holding":
        return _pick_cost(belief, args[0]) if a.value is True else MOVE_ACT
    if name == "In":
        if a.value is not True:
            return MOVE_ACT
        return _pick_cost(belief, args[0]) + MOVE_ACT + _open_cost(belief, args[1])
    if name == "AtPose":
        return 1.0 if belief.held != args[0] else MOVE_ACT
    if name == "NotBlocks":
        return 2 * MOVE_ACT
    if name == "Closable":  # each tall object inside is picked (drawer open) and put down elsewhere
        inside = [o for o in S.TALL if o in belief.particles and belief.particles[o].frame_mass(args[0]) >= 0.05]
        return sum(_pick_cost(belief, o) + MOVE_ACT for o in inside) or 2 * MOVE_ACT
    if name == "Cooked":
        return _pick_cost(belief, args[0]) + 3 * MOVE_ACT
    return 1.0


def _needs_open(a: Atom, belief: Any) -> str | None:
    """The drawer an unmet atom will have to open (to put something in or take it out)."""
    if a.predicate == "In" and a.value is True and a.args[1] in belief.drawers:
        return str(a.args[1])
    if a.predicate == "Closable" and a.value is True and a.args[0] in S.DRAWERS:
        return str(a.args[0])
    if a.predicate in ("Holding", "Cooked") and a.value is True and belief.held != a.args[0]:
        f = _frame_of(belief, str(a.args[0]))
        return f if f in belief.drawers else None
    return None


def estimate(goal: Goal, belief: Any, holds: Callable[[Atom], bool]) -> float:
    """Σ over unmet atoms of :func:`atom_estimate`, plus the drawer interactions additive estimates
    miss: closing again a drawer an unmet atom needs opened while the subgoal wants it closed, and,
    when the subgoal wants the *other* drawer open, closing the first one (and, for an object to be
    held across the switch, setting it down and picking it up again: push needs a free hand)."""
    total = 0.0
    reopen: dict[str, bool] = {}  # drawer -> needed by a Holding atom
    for a in goal.atoms:
        if holds(a):
            continue
        total += atom_estimate(a, belief)
        d = _needs_open(a, belief)
        if d is not None:
            reopen[d] = reopen.get(d, False) or a.predicate == "Holding"
    for d, held in reopen.items():
        closed = next((a for a in goal.atoms if a.predicate == "Open" and a.args == (d,) and a.value is False), None)
        if closed is not None and holds(closed):
            total += atom_estimate(closed, belief)
        if d in S.DRAWERS and any(a.predicate == "Open" and a.value is True and a.args[0] in S.DRAWERS and a.args[0] != d
               for a in goal.atoms):
            total += 2 * MOVE_ACT + (2 * MOVE_ACT if held else 0.0)
    return total
