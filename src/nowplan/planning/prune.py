"""Greedy action elimination for plans that only regression can check (the regression engine's plans).

The forward engine trims its plans by replaying them over states (:mod:`nowplan.planning.postprocess`,
Fink and Yang; Nakhost and Müller).  The regression search plans where no state can be replayed (a
belief unsure of fluents either way, predicates tested on the belief, generators), and its shortcuts
plan a goal's atoms one after another, so a plan may achieve something twice: a held-out feeder
repair (examples/gridfix, flat, seed 0) bought a second spare and replaced a segment it had replaced
already, 7 steps of 40 (benchmarks/results/heldout17/README.md, finding 4).

Here each step in turn is tried out of the plan together with every later step left without a
precondition (checked at its level) by its absence, as the forward elimination drops the steps it
leaves inapplicable: a pass in plan order over the values the kept steps' effects give each fluent,
and the belief's answer for a fluent no kept step has touched yet (:func:`without`).  The rest is
kept if the goal regresses through it at the same levels to a ``g0`` the belief satisfies
(:func:`nowplan.planning.forward.regress_actions`: exact pre-images, the contract's test) and it costs
no more.  Never makes a plan costlier or invalid; plans longer than :data:`MAX_STEPS` are left alone.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Sequence
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action

log = logging.getLogger(__name__)

MAX_STEPS = 200  # the tries regress the plan once each: quadratic in its length


def without(domain: Domain, belief: Any, actions: Sequence[Action], levels: LevelMap, i: int,
            goal: Goal | None = None) -> list[int] | None:
    """The steps that stay when step ``i`` goes: a pass in plan order drops every later step a
    precondition of which (checked at its level) neither the last kept effect on its fluent nor,
    where no kept step touched it, the belief gives.  ``None`` if, so judged, ``goal`` then fails
    (no regression needed to reject the try)."""
    rules, statics = domain.rules, domain.static_predicates
    last: dict[Any, Any] = {}  # fluent -> the value the kept steps so far left it with
    kept: list[int] = []
    for j, a in enumerate(actions):
        if j == i:
            continue
        if j > i:
            ok = True
            for p in a.preconditions(levels.level(a)):
                if p.predicate in statics:
                    continue
                v = last.get(p.key, _UNSET)
                if not (domain.holds(p, belief) if v is _UNSET else rules.rule(p.predicate).entails(v, p.value)):
                    ok = False
                    break
            if not ok:
                continue
        kept.append(j)
        for e in a.effects():
            last[e.key] = e.value
    if goal is not None:
        for g in goal.atoms:
            v = last.get(g.key, _UNSET)
            if not (domain.holds(g, belief) if v is _UNSET else rules.rule(g.predicate).entails(v, g.value)):
                return None
    return kept


_UNSET = object()


def prune(
    domain: Domain, belief: Any, goal: Goal, actions: Sequence[Action], levels: LevelMap,
    cost_of: Callable[[Action], float],
) -> list[tuple[Action | None, Goal]] | None:
    """The plan's steps ``[(None, g0), (a1, g1), …]`` with redundant steps removed, or ``None`` if none
    could be (or the plan is shorter than 2 or longer than :data:`MAX_STEPS` steps)."""
    from nowplan.planning.forward import regress_actions

    plan = list(actions)
    if len(plan) < 2 or len(plan) > MAX_STEPS:
        return None
    best: list[tuple[Action | None, Goal]] | None = None
    i = 0
    while i < len(plan):  # each try removes steps or moves on: bounded by the plan's length
        keep = without(domain, belief, plan, levels, i, goal)
        out = sorted(set(range(len(plan))) - set(keep)) if keep is not None else []
        if keep is not None and all(cost_of(plan[k]) >= 0 for k in out):  # (never costlier)
            rest = [plan[k] for k in keep]
            steps = regress_actions(domain, belief, goal, rest, levels)
            if steps is not None:
                log.info("pruned %d redundant step(s) from a plan of %d: %s", len(out), len(plan),
                         ", ".join(str(plan[k]) for k in out))
                plan, best = rest, steps
                continue  # re-examine from the same position
        i += 1
    return best
