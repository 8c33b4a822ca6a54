"""Atom truths kept for one point state, for the peephole's many tests in the same belief.

Between two actions RCHPN asks ``Domain.holds`` about the same atoms again and again: the
highest true kernel scans each pre-image of a plan (the chain of pre-images repeats most atoms),
the frames pushed in the same belief scan theirs, ``Reorderer.can_follow`` and ``valid`` test
preconditions and ``g0``, and the estimator finds the unmet preconditions of each step.  On a
plain point belief (:func:`~nowplan.planning.grounding_index.point_state`: a ``State``, or a
``SymbolicBelief`` of one) every answer is a function of that immutable state and the atom, so
:class:`TruthMemo` keeps the answers while the belief's state is the same object.  For any other
belief it asks ``Domain.holds`` each time.

Keyed by the atom object's id, with the atom kept in the value (so an id is never reused while
cached): pre-images and operator preconditions are long-lived objects, and an id lookup does not
hash an atom's fields.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.planning.grounding_index import point_state

HoldsFn = Callable[[Atom], bool]

# answers kept for one state before the table is cleared (a bound on its memory; a marsupial
# rewrite asks a few hundred atoms in one state)
_MAX_ATOMS = 100_000


class TruthMemo:
    """``Domain.holds`` per atom, remembered while the belief's point state is the same object."""

    def __init__(self, domain: Domain) -> None:
        self.domain = domain
        self._state: Any = None  # the state the answers are for (kept alive: its id is not reused)
        self._known: dict[int, tuple[Atom, bool]] = {}

    def holds_in(self, belief: Any) -> HoldsFn:
        """A function answering ``Domain.holds(atom, belief)``, memoised for a point belief."""
        domain_holds = self.domain.holds
        state = point_state(belief)
        if state is None:
            return lambda a: domain_holds(a, belief)
        if state is not self._state or len(self._known) > _MAX_ATOMS:
            self._state, self._known = state, {}
        known = self._known

        def holds(a: Atom) -> bool:
            hit = known.get(id(a))
            if hit is not None and hit[0] is a:
                return hit[1]
            r = domain_holds(a, belief)
            known[id(a)] = (a, r)
            return r

        return holds
