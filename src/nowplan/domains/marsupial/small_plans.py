"""The peephole estimator's small plans that marsupial makes without a search (issue 19 target 3).

RCHPN's estimator (:class:`nowplan.acting.resources.Estimator`) asks a small regression search
for the preconditions an abstract step exposes at its next level.  On marsupial those searches
are mostly one of three kinds, whose answer is known without the search
(:attr:`nowplan.acting.resources.ResourceModel.small_plan`, :func:`small_plan`):

* ``in(p, v)`` (a top-level Unload): with ``p`` on the ground where ``v`` goes, the load of ``p``
  there, if its preconditions at its level hold now (:func:`load_plan`);
* ``at(v, l)`` (a Load or Unload one level down): the travel from where ``v`` is, if its
  preconditions at its level hold now (:func:`travel_plan`);
* ``door(v) = p`` (an Unload at the loader's level): the loader's fetch path (:func:`fetch_plan`).

Anything else (a package in another vehicle, a vehicle to pack first, no fetch path …) is left
to the search.  Why these are the search's answers: the only operator adding ``in(p, v)`` is a
Load, whose place generator gives, for a package lying where ``v`` goes, that place alone; the
only one adding ``at(v, l)`` is a Travel, and the one from ``v``'s place is the only child whose
goal holds (h = 0, f = its cost; every other child needs another travel first).  A child whose
goal holds is the A*'s next node, so the plan is that one action.

The fetch path.  RCHPN's SelectGap compares unloads of one vehicle at the loader's level by the effort of each:
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
package out.  Elsewhere it returns None and the estimator searches.  Every answer is compared with the search's on RCHPN runs by
``tests/test_marsupial_small_plans.py``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action, Operator
from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.bay_relaxed import fetch_infeasible
from nowplan.domains.marsupial.grid import Hold, door_package, door_status

# robot operators, Load and Travel per domain, and the cost of an unload and a load (a domain is made once per map;
# its operators never change)
_ROBOT: dict[int, tuple[Domain, dict[str, Operator], float]] = {}
_MAX_STEPS = 64  # a chain of transitions longer than this is not looked for (the cost bound ends it first)


def _robot_ops(domain: Domain) -> tuple[dict[str, Operator], float]:
    known = _ROBOT.get(id(domain))
    if known is None or known[0] is not domain:
        if len(_ROBOT) >= 64:
            _ROBOT.clear()
        ops = {o.name: o for o in domain.operators if o.name.startswith("loader_") or o.name in ("load", "travel")}
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


def _ground_plan(domain: Domain, action: Action, belief: Any, levels: LevelMap) -> tuple[Action, ...] | None:
    """``(action,)`` if its preconditions at its level hold in ``belief``, else None."""
    if all(domain.holds(a, belief) for a in action.preconditions(levels.level(action))):
        return (action,)
    return None


def _place(belief: Any, x: str) -> str | None:
    """Where ``x`` lies (its ``at`` fact), or None (a package in a vehicle)."""
    for args in belief.facts("at"):
        if args and args[0] == x:
            return str(args[1])
    return None


def load_plan(domain: Domain, pkg: str, veh: str, belief: Any, levels: LevelMap) -> tuple[Action, ...] | None:
    """``(load(p, v, l),)`` for ``p`` on the ground at ``l`` where ``v`` goes, its preconditions
    holding; else None."""
    here = _place(belief, pkg)
    op = _robot_ops(domain)[0].get("load")
    if here is None or op is None or not belief.value(("reachable", (here, veh))):
        return None
    return _ground_plan(domain, Action(op, (pkg, veh, here)), belief, levels)


def travel_plan(domain: Domain, veh: str, to: str, belief: Any, levels: LevelMap) -> tuple[Action, ...] | None:
    """``(travel(v, a, l),)`` from ``v``'s place ``a``, its preconditions holding; else None."""
    here = _place(belief, veh)
    op = _robot_ops(domain)[0].get("travel")
    if here is None or here == to or op is None:
        return None
    return _ground_plan(domain, Action(op, (veh, here, to)), belief, levels)


def small_plan(domain: Domain, unmet: Sequence[Atom], belief: Any, levels: LevelMap) -> tuple[Action, ...] | None:
    """The estimator's small plan for ``unmet`` where it is known without a search (module
    docstring), else None: the estimator searches."""
    if len(unmet) != 1:
        return None
    x = unmet[0]
    if x.predicate == "door":
        return fetch_plan(domain, unmet, belief)
    if x.value is not True or len(x.args) != 2:
        return None
    if x.predicate == "in":
        return load_plan(domain, str(x.args[0]), str(x.args[1]), belief, levels)
    if x.predicate == "at" and belief.value(("cargo", (x.args[0],))) is not None:  # a vehicle's place
        return travel_plan(domain, str(x.args[0]), str(x.args[1]), belief, levels)
    return None
