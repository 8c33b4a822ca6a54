"""Resource-use estimates of abstract plan steps (seed 002 III-C).

Achieving a subgoal uses resources, each in one of three ways
(:class:`~nowplan.core.operators.ResourceUse`): *shareable*, *contained* or
*continual*.  The resources of an abstract step are estimated from the
operators' declared resources:

* **0th order** — the resources the concrete operator declares;
* **1st order** — plus the 0th-order resources of the operators in a small
  plan (a limited regression search from the current belief) for the
  preconditions hidden at the step's level that the next level exposes;
* **2nd order** — plus the 1st-order estimates of those operators and the
  0th-order resources of a small plan for the preconditions exposed two
  levels down.

The estimate also records the *effort*: the cost of those small plans, which
says how far the step is from being achievable in the current state (the
greedy tie-breaker of seed 002 Fig. 2).  A domain describes how its
resources behave with a :class:`ResourceModel` it carries (``Domain(resources=...)``).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action, Resource, ResourceUse
from nowplan.errors import ContradictoryGoalError
from nowplan.planning.regression import PlannerConfig, plan

log = logging.getLogger(__name__)

ResourceName = tuple[Any, ...]
# (resource name, actions of the first subgoal, actions of the second, belief) -> can they share
# it now (True), not (False), or no opinion (None: the declared uses decide)
ShareableFn = Callable[[ResourceName, Sequence[Action], Sequence[Action], Any], "bool | None"]
# two different resources that cannot be used at once (e.g. one vehicle at two stops)
ClashFn = Callable[[ResourceName, ResourceName], bool]
# (atoms unmet in the belief, belief) -> a lower bound on the cost of any plan achieving them all
EffortBoundFn = Callable[[Sequence[Atom], Any], float]
# (domain, atoms unmet in the belief, belief, level map) -> the small plan the estimator's search
# would find for them, known to the domain without a search, or None (the estimator searches)
SmallPlanFn = Callable[[Domain, Sequence[Atom], Any, LevelMap], "tuple[Action, ...] | None"]

# the strongest use wins when an estimate meets one resource several times
_STRENGTH = {ResourceUse.SHAREABLE: 0, ResourceUse.CONTAINED: 1, ResourceUse.CONTINUAL: 2}


@dataclass(frozen=True)
class ResourceModel:
    """How a domain's declared resources are estimated and shared.

    ``orders`` gives the estimate order per operator name (default 0);
    ``arrangeable`` names the operators whose abstract steps the peephole
    optimizer may move or combine (``None``: every abstract step);
    ``shareable`` is the domain's test, in the now, whether two subgoals can
    share a resource (for vehicles: does everything still fit); True makes
    it shareable whatever the declared uses, False at best contained, None
    leaves the declared uses;
    ``clash`` says that two distinct resources exclude each other.
    ``arrange`` replaces the rule-based ordering preference altogether.
    ``effort_bound`` is an admissible estimate, in the now, of the cost of a plan for a step's
    exposed preconditions (a lower bound on every plan's cost, hence on the small plan's the
    effort is): ``arrange`` asked whether the second of two steps goes first skips the small
    search where the bound already says it is not easier to reach (:meth:`Estimator.effort_bound`).
    ``small_plan`` gives, for unmet atoms whose plan the domain knows without a search, the plan the
    estimator's small search would find (marsupial: a load, a travel, or the loader's fetch path for
    ``door(v) = p``, which the search only follows one robot operator at a time through their
    generators); None lets the estimator search.  It must be the search's own answer: the effort
    and the resources come from it.
    """

    orders: Mapping[str, int] = field(default_factory=dict, hash=False)
    arrangeable: frozenset[str] | None = None
    shareable: ShareableFn | None = field(default=None, compare=False, hash=False)
    clash: ClashFn | None = field(default=None, compare=False, hash=False)
    arrange: Callable[..., int] | None = field(default=None, compare=False, hash=False)
    effort_bound: EffortBoundFn | None = field(default=None, compare=False, hash=False)
    small_plan: SmallPlanFn | None = field(default=None, compare=False, hash=False)
    # per operator name the resource templates to use instead of the operators' own (derived for a
    # domain that declares none: nowplan.acting.derived_resources); None: the operators' own
    derived: Mapping[str, tuple[Resource, ...]] | None = field(default=None, compare=False, hash=False)

    def order(self, action: Action) -> int:
        return int(self.orders.get(action.name, 0))

    def uses(self, action: Action) -> tuple[Resource, ...]:
        """The resources ``action`` uses: its operator's declared ones, or the derived ones."""
        if self.derived is None:
            return action.resources()
        b = action.bindings
        return tuple(r.bind(b) for r in self.derived.get(action.name, ()))


DEFAULT_MODEL = ResourceModel()


def resource_model(domain: Domain) -> ResourceModel:
    """The domain's own model (``Domain(resources=...)``); else, if some operator declares
    resources, the declared uses at order 0; else the uses derived from the operators
    (:mod:`nowplan.acting.derived_resources`, kept per domain)."""
    if domain.resources is not None:
        return domain.resources
    if any(op.resources for op in domain.operators):
        return DEFAULT_MODEL
    kept = domain.facts.derived.get("derived resources")
    if kept is not None and kept[0] is domain.operators:
        return kept[1]  # type: ignore[no-any-return]
    from nowplan.acting.derived_resources import derive_resources, stops_clash

    model = ResourceModel(orders={op.name: 1 for op in domain.operators}, clash=stops_clash,
                          derived=derive_resources(domain))
    log.info("domain %s declares no resources: the peephole uses resources derived from its operators",
             domain.name)
    domain.facts.derived["derived resources"] = (domain.operators, model)
    return model


@dataclass(frozen=True)
class Estimate:
    """Resources used to achieve a subgoal, and the effort to reach it from the belief.

    ``effort`` is infinite when no small plan reaches the step's exposed
    preconditions from the current belief (only computed for orders >= 1).
    """

    uses: Mapping[ResourceName, ResourceUse] = field(hash=False)
    effort: float = 0.0


def merge_uses(
    into: dict[ResourceName, ResourceUse], resources: Mapping[ResourceName, ResourceUse] | Sequence[Resource]
) -> None:
    items = resources.items() if isinstance(resources, Mapping) else ((r.name, r.use) for r in resources)
    for name, use in items:
        old = into.get(name)
        if old is None or _STRENGTH[use] > _STRENGTH[old]:
            into[name] = use


def hidden_classes(action: Action, level: int) -> list[int]:
    """Criticality classes of ``action`` not kept at ``level``, next-exposed first."""
    return [c for c in action.operator.criticalities if c <= level]


class Estimator:
    """Resource estimates for one belief (cached per action, level and order)."""

    def __init__(
        self,
        domain: Domain,
        objects: Mapping[str, str | None],
        belief: Any,
        model: ResourceModel,
        search: PlannerConfig | None = None,
        holds: Callable[[Atom], bool] | None = None,
    ) -> None:
        self.domain = domain
        self.objects = objects
        self.belief = belief
        # truth in the belief (the caller's memo for it, or Domain.holds)
        self.holds: Callable[[Atom], bool] = holds if holds is not None else (lambda a: domain.holds(a, belief))
        self.model = model
        self.search = search or PlannerConfig(
            max_nodes=300, time_limit=30.0, serialization=True, monotonic=False, shortcut_nodes=300
        )
        self._cache: dict[tuple[Any, int, int], Estimate] = {}
        self._plans: dict[tuple[Any, int], tuple[Action, ...] | None] = {}
        # small plans by what the search is given (the unmet atoms in order, and the level map):
        # steps of different actions with the same unmet preconditions (two loads into one truck
        # waiting for it at the same place) share one search; the belief, domain, objects and
        # search settings are this estimator's own
        self._by_goal: dict[tuple[tuple[Atom, ...], LevelMap], tuple[Action, ...] | None] = {}
        self.plan_calls = 0
        self._cheapest: dict[str, float] = {}

    def estimate(self, action: Action, levels: LevelMap, order: int | None = None) -> Estimate:
        lvl = levels.level(action)
        k = self.model.order(action) if order is None else order
        key = (action.key, lvl, k)
        hit = self._cache.get(key)
        if hit is not None:
            return hit
        uses: dict[ResourceName, ResourceUse] = {}
        merge_uses(uses, self.model.uses(action))
        effort = 0.0
        if k >= 1 and not action.is_primitive(lvl):
            classes = hidden_classes(action, lvl)
            # 1st order: a small plan for the preconditions the next level exposes
            first = self._support(action, levels, classes[0])
            if first is None:
                effort = float("inf")  # not reachable from here with a small search
            else:
                effort += sum(a.cost(self.belief) for a in first)
                for a in first:
                    sub = self.estimate(a, levels, k - 1)
                    merge_uses(uses, sub.uses)
            if k >= 2 and len(classes) > 1:
                # 2nd order: and one for those exposed two levels down (0th order)
                second = self._support(action, levels, classes[1])
                if second is not None:
                    effort += sum(a.cost(self.belief) for a in second)
                    for a in second:
                        merge_uses(uses, self.model.uses(a))
        est = Estimate(uses, effort)
        self._cache[key] = est
        return est

    def effort(self, action: Action, levels: LevelMap) -> float:
        """The cost of a small plan for the preconditions exposed at the next level."""
        lvl = levels.level(action)
        if action.is_primitive(lvl):
            return 0.0
        first = self._support(action, levels, hidden_classes(action, lvl)[0])
        return float("inf") if first is None else sum(a.cost(self.belief) for a in first)

    def effort_bound(self, action: Action, levels: LevelMap) -> float:
        """A lower bound on :meth:`effort`, found without a search.

        The effort itself once its small plan is known; 0 when nothing is exposed or unmet; else
        the larger of two admissible bounds of the unmet atoms (every plan for them costs at
        least that, so the small plan does too): the cheapest operator with an effect on each
        atom's predicate (:meth:`cheapest_achiever`), and the domain's own
        ``ResourceModel.effort_bound`` if it has one.
        """
        lvl = levels.level(action)
        if action.is_primitive(lvl):
            return 0.0
        crit = hidden_classes(action, lvl)[0]
        key = (action.key, crit)
        if key in self._plans:
            known = self._plans[key]
            return float("inf") if known is None else sum(a.cost(self.belief) for a in known)
        unmet = self._unmet(action, crit)
        if not unmet:
            return 0.0
        out = max(self.cheapest_achiever(a.predicate) for a in unmet)
        bound = self.model.effort_bound
        if bound is not None:
            out = max(out, float(bound(unmet, self.belief)))
        return max(out, 0.0)

    def cheapest_achiever(self, predicate: str) -> float:
        """The least cost of an operator with an effect on ``predicate``: a bound on any plan
        that makes an atom of it true.  0 where that does not hold or is not known: a predicate
        decided by a test or derived by axioms (made true by other facts), an operator whose
        cost depends on its arguments or the belief, or no operator at all."""
        hit = self._cheapest.get(predicate)
        if hit is not None:
            return hit
        pred = self.domain.predicates.get(predicate)
        costs: list[float] = []
        if (pred is None or pred.test is None) and predicate not in self.domain.derived:
            for op in self.domain.operators:
                if any(e.predicate == predicate for e in op.effects):
                    costs.append(float(op.cost) if isinstance(op.cost, (int, float)) else 0.0)
        out = min(costs) if costs else 0.0
        self._cheapest[predicate] = out
        return out

    def _unmet(self, action: Action, crit: int) -> list[Atom]:
        """``action``'s preconditions of criticality ``crit`` (not static) that the belief does not satisfy."""
        b = action.bindings
        want = [
            p.atom.bind(b)
            for p in action.operator.preconditions
            if p.criticality == crit and p.atom.predicate not in self.domain.static_predicates
        ]
        holds = self.holds
        return [a for a in want if not holds(a)]

    def _support(self, action: Action, levels: LevelMap, crit: int) -> tuple[Action, ...] | None:
        """Actions of a limited plan achieving ``action``'s unmet preconditions of criticality ``crit``."""
        key = (action.key, crit)
        if key in self._plans:
            return self._plans[key]
        unmet = self._unmet(action, crit)
        out: tuple[Action, ...] | None = ()
        if unmet:
            asked = (tuple(unmet), levels)
            if asked in self._by_goal:
                out = self._by_goal[asked]
            else:
                own = self.model.small_plan
                known = own(self.domain, unmet, self.belief, levels) if own is not None else None
                out = known if known is not None else self.small_plan(unmet, levels)
                self._by_goal[asked] = out
        self._plans[key] = out
        return out

    def small_plan(self, unmet: Sequence[Atom], levels: LevelMap) -> tuple[Action, ...] | None:
        """A fresh limited search from the belief for ``unmet`` (not cached): its actions, or None."""
        try:
            goal = Goal.of(unmet, self.domain.rules)
        except ContradictoryGoalError as err:
            # hidden preconditions that exclude each other (barman's abstract pour: a hand holding
            # the shot and empty): no one small plan reaches them from here
            log.debug("no small plan for %s: %s", list(unmet), err)
            return None
        self.plan_calls += 1
        res = plan(self.domain, self.objects, self.belief, goal, levels, self.search)
        out = res.plan.actions if res.solved and res.plan is not None else None
        if out is None:
            log.debug("no small plan for %s: %s", goal, res.reason)
        return out
