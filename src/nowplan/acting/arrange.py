"""The context-sensitive ordering preference ``arrange(g1, g2, s)`` (seed 002 III-B/C).

``arrange`` answers, for two subgoals of an abstract plan and the current
belief: serialize the first before the second (:attr:`Arrange.FIRST`, the
paper's 0), the second before the first (:attr:`Arrange.SECOND`, 1), or
combine them into one subgoal solved jointly (:attr:`Arrange.COMBINE`, 2).
It compares the resources each subgoal is estimated to use
(:mod:`nowplan.acting.resources`) with the seed's rules:

* a resource *continual* for one subgoal and *contained* for the other:
  the contained one first;
* resources *contained* for both: any order is acceptable, and we take the
  one that is easier to reach from the current state first (greedy, seed
  Fig. 2);
* only *shareable* resources in common: combine;
* nothing in common: keep the order.

Before these rules, a subgoal the estimate cannot reach from the current
state (no small plan for the preconditions its next level exposes) is put
after one it can reach.

A domain may test, in the now, whether two subgoals can really share a
resource (seed 002: a vehicle is shareable if everything fits): a resource
that passes is shareable whatever its declared uses, one that fails is at
best contained.  One addition of ours: a subgoal whose operator needs an
effect of the other (an Unload needing its package's Load) is never
combined with or moved before it — doing both "in parallel" has nothing to
share.
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action, ResourceUse
from nowplan.acting.resources import Estimator, ResourceModel, ResourceName


class Arrange(enum.IntEnum):
    FIRST = 0  # serialize g1 before g2
    SECOND = 1  # serialize g2 before g1
    COMBINE = 2  # achieve them jointly


@dataclass(frozen=True)
class Subgoal:
    """Plan steps taken as one: their operators and the pre-image after the last of them."""

    actions: tuple[Action, ...]
    goal: Goal

    def __str__(self) -> str:
        return " + ".join(str(a) for a in self.actions)


def depends(
    domain: Domain, first: Sequence[Action], second: Sequence[Action], levels: LevelMap | None = None
) -> bool:
    """Does an operator of ``second`` need an effect of one of ``first``?

    Only the preconditions kept at each operator's level in ``levels`` count
    (all of them without ``levels``): details hidden at this level are not
    yet a reason to keep two subgoals apart.
    """
    rules = domain.rules
    effects = {e.key: e for a in first for e in a.effects()}
    for a in second:
        for p in a.preconditions(levels.level(a) if levels is not None else None):
            e = effects.get(p.key)
            if e is not None and rules.rule(p.predicate).entails(e.value, p.value):
                return True
    return False


def subgoal_uses(sg: Subgoal, est: Estimator, levels: LevelMap) -> dict[ResourceName, ResourceUse]:
    from nowplan.acting.resources import merge_uses

    uses: dict[ResourceName, ResourceUse] = {}
    for a in sg.actions:
        merge_uses(uses, est.estimate(a, levels).uses)
    return uses


def arrange(
    s1: Subgoal,
    s2: Subgoal,
    belief: Any,
    *,
    domain: Domain,
    levels: LevelMap,
    estimator: Estimator,
    model: ResourceModel | None = None,
    want: Arrange | None = None,
) -> Arrange:
    """The seed's ``arrange(g1, g2, s)`` from declared resources (or the domain's own).

    With ``want``, the caller only asks whether the verdict is ``want`` (SelectGap
    needs SECOND, SelectParallelOps COMBINE): the answer is ``want`` exactly when the
    full verdict is, and otherwise some other verdict, found without the domain's
    shareability tests that cannot make it ``want`` (:func:`_cannot_be_second`).
    """
    model = model or estimator.model
    if model.arrange is not None:
        return Arrange(model.arrange(s1, s2, belief, domain=domain, levels=levels, estimator=estimator))
    if depends(domain, s1.actions, s2.actions, levels) or depends(domain, s2.actions, s1.actions, levels):
        return Arrange.FIRST
    if want is Arrange.SECOND and _second_ruled_out_by_bound(s1, s2, estimator, levels):
        return Arrange.FIRST
    u1 = subgoal_uses(s1, estimator, levels)
    u2 = subgoal_uses(s2, estimator, levels)
    # a step the estimate cannot reach from here waits for one it can reach (in the now)
    f1 = sum(estimator.estimate(a, levels).effort for a in s1.actions)
    f2 = sum(estimator.estimate(a, levels).effort for a in s2.actions)
    if math.isinf(f1) != math.isinf(f2):
        return Arrange.SECOND if math.isinf(f1) else Arrange.FIRST
    pairs: list[tuple[ResourceName, ResourceUse, ResourceUse]] = [
        (r, u1[r], u2[r]) for r in u1.keys() & u2.keys()
    ]
    if model.clash is not None:
        for r1 in u1:
            for r2 in u2:
                if r1 != r2 and model.clash(r1, r2):
                    pairs.append((r1, ResourceUse.CONTAINED, ResourceUse.CONTAINED))
    if not pairs:
        return Arrange.FIRST
    C, K, S = ResourceUse.CONTINUAL, ResourceUse.CONTAINED, ResourceUse.SHAREABLE
    if want is Arrange.SECOND and _cannot_be_second(s1, s2, pairs, estimator, levels):
        return Arrange.FIRST
    if model.shareable is not None:
        # the domain's test, in the now: a resource that can be shared by these two is
        # shareable whatever the declared uses; one that cannot is at best contained
        tested = []
        for r, a, b in pairs:
            verdict = model.shareable(r, s1.actions, s2.actions, belief)
            if verdict is True:
                a, b = S, S
            elif verdict is False:
                a, b = (K if a is S else a), (K if b is S else b)
            if want is Arrange.COMBINE and (a is not S or b is not S):
                return Arrange.FIRST  # combine needs every shared resource shareable
            tested.append((r, a, b))
        pairs = tested
    # continual for one, contained for the other: the contained one first
    second_first = any(a is C and b is K for _, a, b in pairs)
    first_first = any(a is K and b is C for _, a, b in pairs)
    if second_first != first_first:
        return Arrange.SECOND if second_first else Arrange.FIRST
    if second_first or any(a is C and b is C for _, a, b in pairs):
        return Arrange.FIRST  # contradictory needs (DRP violated): leave the plan alone
    exclusive = any(a is not S or b is not S for _, a, b in pairs)
    if exclusive:
        # any serialization is acceptable: the one easier to reach from here first
        e1 = sum(estimator.effort(a, levels) for a in s1.actions)
        e2 = sum(estimator.effort(a, levels) for a in s2.actions)
        return Arrange.SECOND if e2 < e1 else Arrange.FIRST
    return Arrange.COMBINE


def _second_ruled_out_by_bound(s1: Subgoal, s2: Subgoal, estimator: Estimator, levels: LevelMap) -> bool:
    """A sufficient condition, before ``s2`` is estimated at all, for a verdict other than SECOND.

    ``arrange`` answers SECOND only (a) when ``s2`` is reachable and ``s1`` is not, (b) through
    a pair continual for ``s1`` and contained for ``s2``, or (c) when ``s2`` is easier to reach
    than ``s1`` (see :func:`_cannot_be_second`; ``Reorderer.arrange`` too, for a combination with
    nothing left to share).  With ``s1`` reachable and using nothing continually, only (c) is
    left, and a lower bound of ``s2``'s effort at least ``s1``'s effort rules it out, without
    the small search that would find ``s2``'s effort and its 1st-order resources.
    """
    if any(math.isinf(estimator.estimate(a, levels).effort) for a in s1.actions):
        return False
    if any(u is ResourceUse.CONTINUAL for u in subgoal_uses(s1, estimator, levels).values()):
        return False
    e1 = sum(estimator.effort(a, levels) for a in s1.actions)
    return not math.isinf(e1) and sum(estimator.effort_bound(a, levels) for a in s2.actions) >= e1


def nothing_goes_first(s1: Subgoal, estimator: Estimator, levels: LevelMap, model: ResourceModel) -> bool:
    """A sufficient condition, found from ``s1``'s own estimate, for ``arrange(s1, s2, want=SECOND)``
    not to be SECOND for any ``s2`` (SelectGap then looks at no later step).

    It is :func:`_second_ruled_out_by_bound` for every ``s2`` at once: with ``s1`` reachable, using
    nothing continually and no effort to reach (its exposed preconditions hold), SECOND is left only
    through ``s2`` being easier to reach than ``s1``, and no effort (nor a bound of one) is below 0
    (action costs are not negative).  Not for a domain with its own ``arrange``.
    """
    if model.arrange is not None:
        return False
    if any(math.isinf(estimator.estimate(a, levels).effort) for a in s1.actions):
        return False
    if any(u is ResourceUse.CONTINUAL for u in subgoal_uses(s1, estimator, levels).values()):
        return False
    return sum(estimator.effort(a, levels) for a in s1.actions) <= 0.0


def _cannot_be_second(
    s1: Subgoal,
    s2: Subgoal,
    pairs: Sequence[tuple[ResourceName, ResourceUse, ResourceUse]],
    estimator: Estimator,
    levels: LevelMap,
) -> bool:
    """A sufficient condition, before the domain's shareability tests, for a verdict other than SECOND.

    With both subgoals reachable, ``arrange`` answers SECOND only (a) through a pair
    continual for ``s1`` and contained for ``s2`` — the domain's test never makes a
    use continual, and it can only turn a shareable use of ``s2`` into a contained
    one — or (b) when ``s2`` is easier to reach than ``s1`` (contained pairs, or a
    combination of steps with nothing left to share, ``Reorderer.arrange``).  Neither
    needs the test's answer to be ruled out.
    """
    C = ResourceUse.CONTINUAL
    if any(a is C and b is not C for _, a, b in pairs):
        return False
    e1 = sum(estimator.effort(a, levels) for a in s1.actions)
    e2 = sum(estimator.effort(a, levels) for a in s2.actions)
    return not e2 < e1
