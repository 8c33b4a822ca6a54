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
LOOK_RADIUS = 0.04  # the δ of a look's neighbourhood (nowplan.domains.kitchen.belief.DELTA)
LOOK_MASS = 0.01  # below this belief mass near a pose, AtPose there is a put-down, not a look
LOOK_CAP = 100.0  # a look's cost at the least success probability a plan may count on (1 / MIN_DETECT_P)


def _look(cost: float, priced: bool) -> float:
    """A look as the estimate counts it: its cost, kept finite (a look the belief rules out now is
    priced at the cost bound instead of cutting the subgoal off: the estimate is not a proof), or,
    unpriced, one action."""
    return min(cost, LOOK_CAP) if priced else 1.0


def _unlocalized(belief: Any, o: str, priced: bool = True) -> float:
    """A detection if the belief does not already pin ``o`` down near its mode, at its cost.

    A look's cost is its self-loop cost ``1/p`` (``KitchenBelief.look_cost``), not 1: with the block
    spread over the counter (p ≈ 0.06) a look costs about 16, and counting it as 1 left every
    subgoal before the look about 15 short, so the search at weight 1 expanded every cheaper
    ordering of the other steps first (cook seed 0: 33,986 expansions for a 12-step plan).
    ``priced=False`` counts it as one action (:func:`estimate_in_actions`)."""
    if belief.held == o:
        return 0.0
    if bool(belief.localized_at(o, belief.mode_pose(o))):
        return 0.0
    return _look(belief.cheapest_look(o), priced)


def _tall_inside(belief: Any, d: str) -> int:
    return sum(1 for o in S.TALL if o in belief.particles and belief.particles[o].frame_mass(d) >= 0.05)


def _frame_of(belief: Any, o: str) -> str:
    return "hand" if belief.held == o else str(belief.mode_pose(o).frame)


def _open_cost(belief: Any, f: str) -> float:
    """Pulling a closed drawer (0 for the counter, the stove or an open drawer)."""
    return MOVE_ACT if f in belief.drawers and belief.drawers[f] < 0.2 else 0.0


def _pick_cost(belief: Any, o: str, priced: bool = True) -> float:
    if belief.held == o:
        return 0.0
    return MOVE_ACT + _unlocalized(belief, o, priced) + _open_cost(belief, _frame_of(belief, o))


def _localize_cost(belief: Any, o: str, p: Any, priced: bool = True) -> float:
    """``AtPose(o) = p``: a put-down (after picking ``o`` where it is now, unless held), or, where the belief already has ``o`` near ``p``, a look (its cost)
    after opening ``p``'s drawer and moving each object that hides ``p`` out of the way (pick and
    place aside: 2 × ``MOVE_ACT`` each).  Counting 1 for every such atom let the search wander into
    subgoals that want the block seen in a closed drawer behind another object."""
    if belief.held == o:
        return MOVE_ACT
    frame = getattr(p, "frame", None)
    if frame is None or frame == "hand" or belief.particles[o].mass_near(frame, p.rel(), LOOK_RADIUS) < LOOK_MASS:
        return MOVE_ACT + _pick_cost(belief, o, priced)  # picked where it is now, then put down at p
    blockers = sum(1 for j in belief.objects if j != o and not belief.not_blocks(j, o, p))
    return _look(belief.look_cost(o, p), priced) + _open_cost(belief, frame) + 2 * MOVE_ACT * blockers


def atom_estimate(a: Atom, belief: Any, grasped: frozenset[str] = frozenset(), priced: bool = True) -> float:
    """Actions needed for one unmet atom, from the current belief (a rough additive estimate).

    ``grasped``: objects the same subgoal wants held (an unmet ``Holding(o)``).  A tall object
    in a drawer that must become ``Closable`` is then picked by the action that achieves both
    atoms at once, so its pick is counted once, by ``Holding``; counting it again here made a
    subgoal look worse for having regressed through the put-down that follows the pick.
    ``priced``: a look counts its cost (see :func:`_unlocalized`), else one action.
    """
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
        return _pick_cost(belief, args[0], priced) if a.value is True else MOVE_ACT
    if name == "In":
        if a.value is not True:
            return MOVE_ACT
        return _pick_cost(belief, args[0], priced) + MOVE_ACT + _open_cost(belief, args[1])
    if name == "AtPose":
        return _localize_cost(belief, str(a.args[0]), a.value, priced)
    if name == "NotBlocks":  # the blocker picked (its drawer opened) and set aside
        return MOVE_ACT + _pick_cost(belief, args[0], priced)
    if name == "Closable":  # each tall object inside is picked (drawer open) and put down elsewhere
        inside = [o for o in S.TALL if o in belief.particles and belief.particles[o].frame_mass(args[0]) >= 0.05]
        if inside and all(o in grasped for o in inside):
            return 0.0
        return sum(_pick_cost(belief, o, priced) + MOVE_ACT for o in inside if o not in grasped) or 2 * MOVE_ACT
    if name == "Cooked":
        return _pick_cost(belief, args[0], priced) + 3 * MOVE_ACT
    return 1.0


def _needs_open(a: Atom, belief: Any) -> str | None:
    """The drawer an unmet atom will have to open (to put something in or take it out)."""
    if a.predicate == "In" and a.value is True and a.args[1] in belief.drawers:
        return str(a.args[1])
    if a.predicate == "Closable" and a.value is True and a.args[0] in S.DRAWERS:
        return str(a.args[0])
    if a.predicate in ("Holding", "Cooked", "NotBlocks") and a.value is True and belief.held != a.args[0]:
        f = _frame_of(belief, str(a.args[0]))
        return f if f in belief.drawers else None
    return None


def estimate(goal: Goal, belief: Any, holds: Callable[[Atom], bool], priced: bool = True) -> float:
    """Σ over unmet atoms of :func:`atom_estimate`, plus the drawer interactions additive estimates
    miss: closing again a drawer an unmet atom needs opened while the subgoal wants it closed, and,
    when the subgoal wants the *other* drawer open, closing the first one (and, for an object to be
    held across the switch, setting it down and picking it up again: push needs a free hand).

    Looks count their cost (``priced``): the estimate is in the units of a plan's cost, as a search
    at weight 1 (``nowplan run``'s) needs; :func:`estimate_in_actions` counts them as one action."""
    total = 0.0
    reopen: dict[str, bool] = {}  # drawer -> needed by a Holding atom
    unmet = [a for a in goal.atoms if not holds(a)]
    grasped = frozenset(str(a.args[0]) for a in unmet if a.predicate == "Holding" and a.value is True)
    for a in unmet:
        total += atom_estimate(a, belief, grasped, priced)
        d = _needs_open(a, belief)
        if d is not None:
            reopen[d] = reopen.get(d, False) or a.predicate == "Holding"
    for d, held in reopen.items():
        closed = next((a for a in goal.atoms if a.predicate == "Open" and a.args == (d,) and a.value is False), None)
        if closed is not None and holds(closed):
            total += atom_estimate(closed, belief, priced=priced)
        if d in S.DRAWERS and any(a.predicate == "Open" and a.value is True and a.args[0] in S.DRAWERS and a.args[0] != d
               for a in goal.atoms):
            total += 2 * MOVE_ACT + (2 * MOVE_ACT if held else 0.0)
    return total


def estimate_in_actions(goal: Goal, belief: Any, holds: Callable[[Atom], bool]) -> float:
    """:func:`estimate` with every look counted as one action: a distance in actions, for the greedy
    search of the Table I reproduction (weight 10, :mod:`nowplan.domains.kitchen.repro`), whose
    figures were measured with it; priced looks there made hard Swap 3 run out of its 60 actions
    (problems 0-3 of each task, ``both``: 413 actions before, 458 and one failure with them)."""
    return estimate(goal, belief, holds, priced=False)
