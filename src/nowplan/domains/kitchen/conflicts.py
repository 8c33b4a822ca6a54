"""The kitchen's conflict rules: pairs of fluents that cannot hold together, so regression prunes them.

Keyed rules (at most one true atom per key): one thing in the hand, an object
held or in one frame, one drawer open.  Pairwise rules: a pose against being
held or in another frame, ``Closable`` against a tall object inside, and
occlusion through planned placements (:class:`Occludes`).
"""

from __future__ import annotations

from typing import Any

from nowplan.core.atoms import Atom
from nowplan.domains.kitchen import scene as S
from nowplan.domains.kitchen.belief import KitchenBelief, Pose

class _OneInHand:
    """Keyed conflict: at most one of ``HandEmpty`` and ``Holding(o)`` (any o) is true."""

    def group_keys(self, a: Atom) -> list[Any]:
        return [("hand",)] if a.value is True and a.predicate in ("HandEmpty", "Holding") else []

    def __call__(self, a: Atom, b: Atom) -> bool:
        ka = self.group_keys(a)
        return bool(ka) and ka == self.group_keys(b) and a != b


class _OnePlace:
    """Keyed conflict: an object is held or in one frame (``Holding(o)``, ``In(o, f)``)."""

    def group_keys(self, a: Atom) -> list[Any]:
        return [("place", a.args[0])] if a.value is True and a.predicate in ("Holding", "In") else []

    def __call__(self, a: Atom, b: Atom) -> bool:
        ka = self.group_keys(a)
        return bool(ka) and ka == self.group_keys(b) and a != b


class _OneDrawerOpen:
    """Keyed conflict: at most one drawer is open (``pull`` needs the other one closed)."""

    def group_keys(self, a: Atom) -> list[Any]:
        return [("drawer",)] if a.value is True and a.predicate == "Open" and a.args[0] in S.DRAWERS else []

    def __call__(self, a: Atom, b: Atom) -> bool:
        ka = self.group_keys(a)
        return bool(ka) and ka == self.group_keys(b) and a != b


def _pose_clash(a: Atom, b: Atom) -> bool:
    """``AtPose(o) = p`` against ``Holding(o)`` / ``In(o, f)`` elsewhere; ``Closable(f)`` against a tall
    object in f."""
    if a.predicate == "AtPose" and isinstance(a.value, Pose) and b.value is True and b.args[:1] == a.args[:1]:
        if b.predicate == "Holding":
            return a.value.frame != "hand"
        if b.predicate == "In":
            return a.value.frame != b.args[1]
    if a.predicate == "Closable" and a.value is True and b.predicate == "In" and b.value is True:
        return b.args[0] in S.TALL and b.args[1] == a.args[0]
    return False


CONFLICTS = (_OneInHand(), _OnePlace(), _OneDrawerOpen(), _pose_clash)


class Occludes:
    """``AtPose(o) = P`` against ``NotBlocks(o, j, p)`` when ``o`` set down at ``P`` hides ``j`` near ``p``.

    Occlusion then regresses through planned placements: a plan that puts ``o``
    down and then looks for ``j`` cannot put it where it hides ``j`` (the
    detection's visibility precondition is otherwise tested against the belief
    of the moment, in which a held ``o`` hides nothing).  The geometry is the
    test ``place_aside``'s generator uses: the box of ``o`` at ``P`` cuts the
    camera's ray to some point of ``j``'s δ-neighbourhood of ``p`` (memoised
    per belief version).
    """

    def __init__(self, belief: KitchenBelief) -> None:
        self.b = belief
        self._memo: dict[tuple[Any, ...], bool] = {}

    def __call__(self, a: Atom, b: Atom) -> bool:
        if a.predicate != "AtPose" or b.predicate != "NotBlocks" or b.value is not True:
            return False
        place, (blocker, target, tpose) = a.value, b.args
        if not isinstance(place, Pose) or place.frame == "hand" or not isinstance(tpose, Pose):
            return False
        if a.args[0] != blocker or blocker == target or tpose.frame == "hand":
            return False
        key = (blocker, place, target, tpose, self.b.version)
        got = self._memo.get(key)
        if got is None:
            if len(self._memo) > 50_000:
                self._memo.clear()
            xj = (self.b.origins()[place.frame] + place.rel())[None, :]
            region = self.b.region_of(str(target), tpose)
            got = self._memo[key] = bool(self.b.blocks(str(target), str(blocker))(region, xj).any())
        return got
