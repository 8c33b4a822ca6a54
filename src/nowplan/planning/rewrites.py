"""Ties in the regression A*: pure rewrites of held facts, and steps that only re-achieve what holds.

A subgoal's fact that holds may be regressed through a zero-cost operator into other facts that
hold (a *pure rewrite*: marsupial's held ``same_city(p, v)`` into the ``at(p, l)`` it is inferred
from).  The child has its parent's cost and unmet facts.  Only a plan that undoes the fact and
infers it again needs it (``PlannerConfig.held_rewrites``): if no step regressed after the
rewrite conflicts with the fact (an effect that changes it or excludes it, a precondition that
excludes it), the same steps regress from the parent, the fact kept as it holds, at the same
cost.  Yet on a plateau of equal ``f`` A* met every subset of such facts rewritten.

So the frontier is ordered by ``(f, h, r, idle, stamp)``:

* ``r`` counts the pure rewrites on the path (:func:`pure_rewrite`): among equal ``(f, h)``
  the subgoals reached by fewer rewrites come first;
* ``idle`` is 1 for a step whose effects set no unmet fact of its parent (:func:`idle`: it
  only re-achieves facts that hold), 0 for one that makes progress;
* the stamp is eager generation's order (:mod:`nowplan.planning.deferred`).

Only the order among equal ``(f, h)`` changes, so A* keeps its plans' costs, and every
rewrite is still made, so a plan that needs one is still found.  A pure rewrite child takes
its parent's estimate (the same unmet facts; not where the domain gives its own estimate).
The deferred entry of a held fact whose achievers name no unmet fact of the node is bounded by
the node's whole estimate and has ``idle`` 1 (every child keeps the unmet facts;
:meth:`~nowplan.planning.deferred.Reach.bound_all`): ``h`` is an admissible estimate of those
facts, which every plan through such a child must still achieve, so the bound never exceeds the
cost of a plan through the entry.
"""

from __future__ import annotations

from collections.abc import Callable

from nowplan.planning.subgoals import ActionFacts, NodeIndex


def pure_rewrite(fs: frozenset[int], pre: frozenset[int], fholds: Callable[[int], bool]) -> bool:
    """Whether ``pre`` only trades facts of ``fs`` that hold for new facts that hold.

    Through a zero-cost operator such a child has its parent's cost and unmet facts, and asks
    more of the belief (it names facts the parent does not); a child that only drops held
    facts (``pre`` a subset of ``fs``) is weaker than its parent and is not a pure rewrite.
    """
    new = pre - fs
    if not new:
        return False
    return all(fholds(f) for f in new) and all(fholds(f) for f in fs - pre)


def idle(index: NodeIndex, info: ActionFacts, fholds: Callable[[int], bool]) -> int:
    """1 if the action's effects set no fluent of an unmet fact of the node (it only re-achieves), else 0."""
    nf = index.by_fluent
    for flu, _ in info.eff_fl:
        o = nf.get(flu)
        if o is not None and not fholds(o):
            return 0
    return 1
