"""The regression planner's search: A* over subgoals as sets of fact ids.

:class:`_Search` holds one planning call's state (grounder, caches of what
holds, the heuristic in use) and runs A* backwards from a goal, optionally
serialized or monotonic (seed 002 V-B); :func:`nowplan.planning.regression.plan`
drives it.
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Hashable, Mapping, Sequence
from typing import Any

from nowplan.belief.protocols import GivesUp, HasUnknowns, ListsFacts, offers
from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.config import PlannerConfig, _clock
from nowplan.planning.context import PlanningContext
from nowplan.planning.deferred import Expansion
from nowplan.planning.ground_task import GroundTask
from nowplan.planning.h2 import PairReach, pair_reach, start_facts
from nowplan.planning.grounding import Grounder
from nowplan.planning.hadd_kernel import CostsUnavailable, KernelHadd, kernel_hadd
from nowplan.planning.hadd_relevant import RelevantHadd
from nowplan.planning.heuristics import ground_task, relax_unsupported, lazy_by_default
from nowplan.planning import regression_native
from nowplan.planning.plan import PlanStatus
from nowplan.planning.preimage import static_drop
from nowplan.planning.relaxed import LazyRelaxed, Supporter
from nowplan.planning.regression_astar import astar
from nowplan.planning.rewrites import pure_rewrite
from nowplan.planning.subgoals import ActionFacts, action_facts
from nowplan.planning.successors import Successors

# the planner's logger: its fallbacks are reported where they always were
log = logging.getLogger("nowplan.planning.regression")


_RELAXED = {"hadd": "add", "hmax": "max", "hff": "ff", "lmcut": "lmcut"}

_FALLBACKS_LOGGED: set[tuple[str, str, str]] = set()


def _log_fallback(domain: str, heuristic: str, why: str, *, lazy: bool = False) -> None:
    """Say once per (domain, heuristic, reason) that the planner counts unmet atoms instead
    (``lazy``: that it relaxes lazily over the achievers it finds instead of the ground task)."""
    key = (domain, heuristic, why + " lazy" * lazy)
    if key not in _FALLBACKS_LOGGED:
        _FALLBACKS_LOGGED.add(key)
        if lazy:
            log.info("domain %s: heuristic %s relaxes lazily (over the achievers found from each subgoal, "
                     "not the ground task): %s", domain, heuristic, why)
            return
        log.info(
            "domain %s: heuristic %s falls back to counting unmet atoms: %s "
            "(PlannerConfig(lazy_relaxation=True) keeps a relaxed estimate with tests and generators: "
            "DomainSpec(planner=...) or parse_strategy(..., planner=...); generators that all declare "
            "reads=reads_nothing get it by default)",
            domain, heuristic, why,
        )



class _Search:
    """A* over subgoals as frozensets of fact ids (:mod:`nowplan.planning.subgoals`)."""

    # defer the successors of facts that hold (nowplan.planning.deferred); False makes them all at once (tests)
    defer_held = True
    # postpone the successors of unmet facts whose bound lies above their parent's (deferred.Postponed);
    # with defer_held only (False: made at once, tests)
    postpone_unmet = True
    # run the calls the compiled loop can run there (nowplan.planning.regression_native); False: Python (tests)
    native = True

    def __init__(
        self,
        domain: Domain,
        objects: Mapping[str, str | None],
        belief: Any,
        levels: LevelMap,
        config: PlannerConfig,
        context: PlanningContext | None,
    ) -> None:
        self.domain = domain
        self.belief = belief
        self.levels = levels
        self.config = config
        self.now = _clock(config)
        self.deadline = self.now() + config.time_limit
        self.table = domain.facts
        lists = offers(belief, ListsFacts)
        self.grounder = Grounder(domain, objects, belief, context, config.max_generator_values, lists)
        self.drop = static_drop(domain, belief, lists)
        self._holds: dict[Atom, bool] = {}
        self._fholds: dict[int, bool] = {}
        self._hv: dict[int, float] = {}
        self._costs: dict[tuple[str, tuple[Any, ...]], float] = {}
        self._held: set[int] = set()  # the facts fholds found true
        self._zero_preds: frozenset[str] | None = None  # predicates an operator that may cost 0 changes
        kept = self.grounder.per_state
        if kept is not None:  # a plain point belief: the calls from its state share the tests and costs
            self._holds, self._fholds, self._costs, self._held = kept.holds, kept.fholds, kept.costs, kept.held
        self.expanded = 0
        self.generated = 0
        self.min_cost = min(
            (float(o.cost) for o in domain.operators if not callable(o.cost)), default=1.0
        )
        self.min_cost = max(self.min_cost, 0.0)
        self.hadd: RelevantHadd | KernelHadd | None = None  # ground h_add by fact id, explored from the facts asked for
        self.relaxed: LazyRelaxed | None = None
        # a domain's own estimate, fn(goal, belief, holds) -> cost, passed as context.extras["heuristic"]
        self.domain_h = context.extras.get("heuristic") if context is not None else None
        # first steps learnt not to be refinable from this belief (context.extras["forbidden_first"], a
        # set of action keys, see nowplan.acting.backtrack): a plan may not start with one of them
        self.forbidden_first: frozenset[Any] = frozenset(
            context.extras.get("forbidden_first", ()) if context is not None else ())
        # the domain's generators may give up on this call (GivesUp): the search ends, with their reason
        self.gave_up: Callable[[], str | None] | None = (
            (lambda: belief.planning_gave_up(context)) if offers(belief, GivesUp) else None)
        self._no_relax = relax_unsupported(self.grounder, belief)
        self._can_relax = self._no_relax is None
        # with a belief that lists its facts and boolean predicates without tests, truth is membership
        self._true_ids: frozenset[int] | None = None
        self._unknowns: frozenset[Any] = belief.unknowns() if offers(belief, HasUnknowns) else frozenset()
        if self._can_relax:
            self.true_ids()
        self._relaxers: dict[bool, LazyRelaxed] = {}  # by additive propagation: add/ff, max/lmcut
        self._ground_hadd: RelevantHadd | KernelHadd | None = None
        self._task: GroundTask | None = None
        self._pairs: tuple[PairReach | None] | None = None  # (the h2 table, grown to this call's start)
        self._ctx: tuple[frozenset[int], Goal] | None = None
        self._goals: dict[frozenset[int], Goal] = {}
        self._successors = Successors(self.table, self.grounder, levels, self.drop, self.cost)
        for name in (config.heuristic, config.shortcut_heuristic or config.heuristic):
            if name not in (*_RELAXED, "count"):
                from nowplan.errors import UsageError

                raise UsageError(f"PlannerConfig heuristic {name!r}: use hadd, hmax, hff, lmcut or count")
        self.use(config.heuristic)

    def release(self) -> None:
        """Forget everything once the call is over: its helpers hold bound methods of this search
        (the successor generator its costs, the relaxed explorations its supporters and tests),
        cycles that kept the call's nodes, tables and explorations alive until the collector's next
        pass; without them the call's memory is freed when it returns.  Not used afterwards."""
        self.__dict__.clear()

    def use(self, name: str) -> None:
        """Estimate with ``name`` from now on (explorations are shared: h_max with LM-cut, h_add with h_FF)."""
        self.relaxed = self.hadd = None
        kind = _RELAXED.get(name)
        if callable(self.domain_h) or kind is None:
            return
        # a domain whose only obstacle to the ground relaxation is a tested predicate (a user's belief
        # test such as "the item may be there") is relaxed lazily rather than estimated by counting
        # unmet atoms, which left a blind search (a held-out search domain: 38k nodes for a 10-step plan)
        lazy = self.config.lazy_relaxation
        if not lazy and not self._can_relax and lazy_by_default(self.grounder.domain):
            lazy = True
            _log_fallback(self.grounder.domain.name, name, str(self._no_relax), lazy=True)
        if lazy or (kind != "add" and self._can_relax):
            additive = kind in ("add", "ff")
            r = self._relaxers.get(additive)
            if r is None:
                r = self._relaxers[additive] = LazyRelaxed(self._supporters, self.fholds, kind, self._context_key,
                                                               park=True, maybe_zero=self.maybe_zero)
            r.kind = kind
            self.relaxed = r
        elif self._can_relax:
            if self._ground_hadd is None:
                task = ground_task(self.grounder, self.drop)
                hadd: KernelHadd | None = None
                if kernel_hadd(task, self.levels.top, variable_costs=True):  # one compiled exploration of every action
                    try:
                        hadd = KernelHadd(task, self.levels, self.true_ids(), self.cost)
                    except CostsUnavailable:  # a cost to be asked only where the search needs it
                        hadd = None
                if hadd is not None:
                    self._ground_hadd = hadd
                else:
                    self._ground_hadd = RelevantHadd(self.grounder, self.levels, self.drop, self.cost, self.true_ids())
                self._task = task
                self._successors.task = task
                self.grounder.use_task(task)  # generator-free achievers read off the ground task
            self.hadd = self._ground_hadd
        else:
            _log_fallback(self.grounder.domain.name, name, str(self._no_relax))

    def pairs(self) -> PairReach | None:
        """The h² table grown to this call's start (``PlannerConfig.h2``), or ``None`` where it is
        off, a generator binds arguments the ground task cannot list, or the belief lists no facts."""
        if self._pairs is None:
            pr: PairReach | None = None
            if self.config.h2 and self.grounder.lists_facts and not any(op.generators for op in self.domain.operators):
                pr = pair_reach(ground_task(self.grounder, self.drop), self.domain)
                if pr is not None:
                    pr.start_from(start_facts(self.table, self.belief, self.true_ids()))
            self._pairs = (pr,)
        return self._pairs[0]

    def _goal_of(self, context: frozenset[int]) -> Goal:
        if self._ctx is None or self._ctx[0] is not context:
            g = self._goals.get(context)
            if g is None:  # (the relaxation's contexts: a subgoal estimated, an action's preconditions)
                g = self._goals[context] = self.table.goal(context)
            self._ctx = (context, g)
        return self._ctx[1]

    def _context_key(self, f: int, context: frozenset[int]) -> Hashable | None:
        """What the generators behind fact ``f``'s achievers read of ``context`` (``None``: nothing)."""
        a = self.table.atoms[f]
        if self.grounder.goal_free(a):
            return None
        return self.grounder.reading(a, self._goal_of(context))

    def _supporters(self, f: int, context: frozenset[int]) -> list[Supporter]:
        """The relaxation's achievers of fact ``f``: the grounder's, with ``context`` as their goal."""
        a = self.table.atoms[f]
        out: list[Supporter] = []
        for act in self.grounder.achievers(a, lambda: self._goal_of(context)):
            info = action_facts(self.table, act, self.levels.level(act), self.drop)
            out.append((act, self.cost(act), info.pre))
        return out

    def maybe_zero(self, f: int) -> bool:
        """Can fact ``f`` cost 0 in the relaxation: it holds, or an operator that may cost 0 changes its predicate?"""
        if self.fholds(f):
            return True
        zero = self._zero_preds
        if zero is None:
            zero = self._zero_preds = frozenset(
                e.predicate for o in self.domain.operators if callable(o.cost) or float(o.cost) <= 0.0
                for e in o.effects)
        return self.table.atoms[f].predicate in zero

    def holds(self, a: Atom) -> bool:
        r = self._holds.get(a)
        if r is None:
            r = self.domain.holds(a, self.belief)
            self._holds[a] = r
        return r

    def fholds(self, f: int) -> bool:
        r = self._fholds.get(f)
        if r is None:
            true = self._true_ids
            a = self.table.atoms[f]
            if true is None or a.predicate not in self.domain.predicates or (
                    a.value is False and a.key in self._unknowns):
                r = self.holds(a)  # (a negative literal on a fluent the belief is unsure of: it does not hold)
            else:  # boolean predicates without tests: a lookup in the belief's facts
                r = f in true if a.value is not False else self.table.by_key.get((a.predicate, a.args, True)) not in true
            self._fholds[f] = r
            if r:
                self._held.add(f)
        return r

    def true_ids(self) -> frozenset[int]:
        """The ids of the facts the belief lists (it does: only asked where the relaxation can run)."""
        if self._true_ids is None:
            if self._can_relax:  # boolean predicates: each listed fact is true
                get, id_of = self.table.by_key.get, self.table.id_of
                keys = [(p, args, True) for p in self.domain.predicates for args in self.belief.facts(p)]
                ids = list(map(get, keys))
                if None in ids:
                    ids = [id_of(*k) if f is None else f for f, k in zip(ids, keys, strict=True)]
                self._true_ids = frozenset(ids)  # type: ignore[arg-type]
            else:
                self._true_ids = self.table.ids_of(self.belief.atoms())
        return self._true_ids

    def unmet(self, fs: frozenset[int]) -> list[int]:
        """The facts of ``fs`` that do not hold, in ``fs``'s order."""
        fholds = self.fholds
        return [f for f in fs.difference(self._held) if not fholds(f)]

    def satisfied(self, fs: frozenset[int]) -> bool:
        known = self._fholds.get
        for f in fs.difference(self._held):
            r = known(f)
            if not (self.fholds(f) if r is None else r):
                return False
        return True

    def h(self, fs: frozenset[int]) -> float:
        if callable(self.domain_h):
            return float(self.domain_h(self.table.goal(fs), self.belief, self.holds))
        if self.relaxed is not None:
            return self.relaxed.estimate(fs)
        if self.hadd is not None:
            if isinstance(self.hadd, KernelHadd):
                try:  # every fact valued, 0 where it holds (see hadd_kernel)
                    return sum(map(self.hadd.values.__getitem__, fs))
                except IndexError:
                    pass  # a fact newer than the task: asked one by one
            hv = self._hv
            try:
                return sum(map(hv.__getitem__, fs))  # every fact valued (0 if it holds) in this call
            except KeyError:
                pass
            ask = [f for f in fs if f not in hv and not self.fholds(f)]
            if ask:
                self.hadd.extend(ask)  # one exploration for the facts new to the closure
            total = 0.0
            for f in fs:
                x = hv.get(f)
                if x is None:
                    x = hv[f] = 0.0 if self.fholds(f) else self.hadd.get(f)
                total += x
            return total
        unmet = sum(1 for f in fs if not self.fholds(f))
        return unmet * (self.min_cost if self.min_cost > 0 else 1.0)

    def cost(self, act: Action) -> float:
        fixed = act.operator.cost
        if not callable(fixed):
            return float(fixed)
        c = self._costs.get(act.key)
        if c is None:
            c = act.cost(self.belief)
            self._costs[act.key] = c
        return c

    def run(
        self,
        goal: Goal,
        max_nodes: int,
        order: Sequence[Atom] | None = None,
        protect: frozenset[Atom] = frozenset(),
    ) -> tuple[PlanStatus, list[tuple[Action | None, Goal]] | None, str]:
        """A* from ``goal``; ``order`` = serialization, ``protect`` = monotonic atoms
        (:func:`nowplan.planning.regression_astar.astar`; the compiled loop of
        :mod:`nowplan.planning.regression_native` where it gives the same answer faster)."""
        if self.native:
            out = regression_native.run(self, goal, max_nodes, order, protect)
            if out is not None:
                return out
        return astar(self, goal, max_nodes, order, protect)

    def pure_rewrite(self, fs: frozenset[int], pre: frozenset[int]) -> bool:
        """Whether ``pre`` only trades facts of ``fs`` that hold for new facts that hold (:func:`rewrites.pure_rewrite`)."""
        return pure_rewrite(fs, pre, self.fholds)

    def _listed_before(self, x: Expansion, act: Action, info: ActionFacts, ti: int) -> tuple[int, int] | None:
        """``(target, achiever)`` where ``act`` comes first among the held targets before ``x.allowed[ti]``."""
        T = self.table
        best: tuple[int, int] | None = None
        by_fluent, pos = x.index.by_fluent, x.pos
        for e in info.all_effs:
            o = by_fluent.get(T.fluent[e])
            if o is None:
                continue
            p = pos.get(o)
            if p is None or p >= ti or (best is not None and p >= best[0]) or not self.fholds(o):
                continue
            if o != e and not T.entails(e, o):
                continue
            for j, tpl in enumerate(self._successors(o, x.goal_of)):
                if tpl[0] is act:
                    best = (p, j)
                    break
        return best

    def _path(
        self,
        node: tuple[frozenset[int], int],
        parent: Mapping[tuple[frozenset[int], int], tuple[tuple[frozenset[int], int], Action] | None],
    ) -> list[tuple[Action | None, Goal]]:
        T = self.table
        steps: list[tuple[Action | None, Goal]] = [(None, T.goal(node[0]))]
        cur = node
        while True:
            link = parent[cur]
            if link is None:
                break
            prev, act = link
            steps.append((act, T.goal(prev[0])))
            cur = prev
        return steps
