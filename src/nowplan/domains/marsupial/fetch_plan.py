"""The peephole estimator's small plan for ``door(v) = p``, read off the loader's fetch path.

RCHPN's SelectGap compares unloads of one vehicle at the loader's level by the effort of each:
the cost of a small plan for the ``door(v) = p`` the unload exposes (seed 002 Fig. 2's greedy
choice: the package easiest to dig out first).  The estimator's regression search finds that plan
only through the robot operators' generators, which hand it the loader's fetch path
(:func:`nowplan.domains.marsupial.model._transition`) one transition at a time, from the last back
to the bay as it is: one expansion, and one grounding of every achiever, per robot operator.
:func:`fetch_plan` walks the same transitions back itself (the same :data:`~.loader.CACHE` calls,
so the same path) and gives the estimator the plan without the search
(:attr:`nowplan.acting.resources.ResourceModel.small_plan`).

It answers only where the path is the search's answer: a package in the vehicle's bay, a path
found, and cheaper than the one other kind of plan for the atom, an unload of the package and a
load of it again (two vehicle operators), which the search finds when the loader cannot dig the
package out.  Elsewhere it returns None and the estimator searches.  Measured on the RCHPN runs of
``both`` and ``single`` with 5-10 packages, trials 0-1: 373 small plans answered, every one equal
to the search's (``tests/test_marsupial_fetch_plan.py`` checks every answer of RCHPN runs).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.core.operators import Action, Operator
from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.bay_relaxed import fetch_infeasible
from nowplan.domains.marsupial.grid import Hold, door_package, door_status

# robot operators per domain, and the cost of an unload and a load (a domain is made once per map;
# its operators never change)
_ROBOT: dict[int, tuple[Domain, dict[str, Operator], float]] = {}
_MAX_STEPS = 64  # a chain of transitions longer than this is not looked for (the cost bound ends it first)


def _robot_ops(domain: Domain) -> tuple[dict[str, Operator], float]:
    known = _ROBOT.get(id(domain))
    if known is None or known[0] is not domain:
        if len(_ROBOT) >= 64:
            _ROBOT.clear()
        ops = {o.name: o for o in domain.operators if o.name.startswith("loader_")}
        costs = [float(o.cost) for o in domain.operators
                 if o.name in ("load", "unload") and isinstance(o.cost, (int, float))]
        bound = sum(costs) if len(costs) == 2 else 0.0  # 0: never answer (no such operators)
        known = _ROBOT[id(domain)] = (domain, ops, bound)
    return known[1], known[2]


def fetch_plan(domain: Domain, unmet: Sequence[Atom], belief: Any) -> tuple[Action, ...] | None:
    """The robot operators that bring ``p`` to the load anchor, for ``unmet == [door(v) = p]`` with
    ``p`` in ``v``'s bay; None (the estimator searches) for any other atoms, or when the loader finds
    no path or one that costs as much as an unload and a load."""
    if len(unmet) != 1:
        return None
    x = unmet[0]
    pkg = x.value
    if x.predicate != "door" or not isinstance(pkg, str) or door_package(pkg) != pkg:
        return None
    veh = str(x.args[0])
    hold = belief.value(("cargo", (veh,)))
    if not isinstance(hold, Hold):
        return None
    door = lp.door_of(str(belief.value(("door", (veh,)))), dict(belief.facts("shape")))
    if pkg not in hold.packages() and (door is None or door[0] != pkg):
        return None
    ops, bound = _robot_ops(domain)
    start = (hold, door)
    # the generators' call (model._transition): the same cached search, the same path
    path = lp.CACHE.path(start, f"fetch:{pkg}", lp.fetch_goal(pkg), lp.fetch_h(pkg),
                         infeasible=lambda c: fetch_infeasible(c[0], c[1], pkg))
    if not path:
        return None
    status = door_status(*start)
    rest: list[Action] = []
    t: lp.Transition | None = path[-1]
    cost = 0.0
    for _ in range(_MAX_STEPS):
        if t is None:
            return None
        op = ops.get(f"loader_{t.kind}")
        if op is None or not isinstance(op.cost, (int, float)):
            return None
        rest.append(Action(op, (veh, t.arg, t.before[0], t.after[0], t.door_before, t.door_after)))
        cost += float(op.cost)
        if cost >= bound:
            return None
        if t.before[0] == hold and t.door_before == status:
            rest.reverse()
            return tuple(rest)
        # regression's next goal is the transition's start (cargo and door): the robot generators
        # find the transition into it among the paths known from the bay (model._transition)
        t = lp.CACHE.into(start, t.before[0], t.door_before)
    return None
