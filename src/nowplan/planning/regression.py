"""Regression (pre-image backchaining) A* over an abstraction level.

``plan(...)`` searches backwards from the goal γ: a node is a subgoal G (a
conjunction), a successor is the pre-image of G under an operator instance
ω at ω's level (seed 002 II-A/B), and the search stops at a subgoal the
current belief satisfies.  HPN's shortcuts (seed 002 V-B) run first when
switched on: a random serialization of the goal's conjuncts, then a
monotonic plan (never undoing a goal fluent that already holds), then full
backward search.  Limits end the search with a typed :class:`PlanResult`.
"""

from __future__ import annotations

import gc
import heapq
import math
import itertools
import logging
import random
import time
from collections.abc import Callable, Hashable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal

from nowplan.core.atoms import Atom, Goal, conjoin, contradiction
from nowplan.belief.protocols import ListsFacts
from nowplan.core.domain import Domain
from nowplan.core.facts import FactTable
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.context import PlanningContext
from nowplan.planning.ground_task import GroundTask
from nowplan.planning.grounding import Grounder
from nowplan.planning.hadd_kernel import KernelHadd, kernel_hadd
from nowplan.planning.hadd_relevant import RelevantHadd
from nowplan.planning.heuristics import ground_task, relax_unsupported
from nowplan.planning.relaxed import LazyRelaxed, Supporter
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.subgoals import NodeIndex, action_facts, regress
from nowplan.planning.successors import Successors

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class PlannerConfig:
    """Settings of the regression planner (budgets, heuristic, search options)."""

    max_nodes: int = 50_000  # expansions for the full search
    time_limit: float = 60.0  # seconds for one call (all methods), on ``clock``
    # "wall" (elapsed time) or "cpu" (this process's CPU time: the same searches end on a loaded
    # machine as on a quiet one, for experiments)
    clock: Literal["wall", "cpu"] = "wall"
    weight: float = 1.0  # f = g + weight * h
    serialization: bool = True  # HPN shortcut 1
    monotonic: bool = True  # HPN shortcut 2
    shortcut_nodes: int = 2_000  # expansions allowed to each shortcut
    max_generator_values: int = 8
    seed: int = 0
    # hadd | hmax | hff | lmcut: relaxed costs from the belief (HSPr-style; h_max and LM-cut admissible);
    # count: unmet atoms x cheapest cost.
    # Without lazy_relaxation the relaxed ones need the whole ground task (a belief that lists its
    # facts, no generators or tested predicates) and fall back to count otherwise.
    heuristic: str = "hadd"
    # relax over the achievers the grounder finds, explored on demand from the subgoals' atoms
    # (works with generators and tested predicates; heuristics.LazyRelaxed)
    lazy_relaxation: bool = False
    # the estimate for the random-serialization shortcut (None: ``heuristic``); e.g. h_max there, where
    # one conjunct at a time is searched, and LM-cut for the searches of whole conjunctions
    shortcut_heuristic: str | None = None
    # "auto": search forward (nowplan.planning.forward) where the belief lists its facts and the
    # domain has no generators or tested predicates, else regress; "forward" | "regression" force one
    engine: Literal["auto", "forward", "regression"] = "auto"
    # the forward search: LAMA's first iteration (h_FF and landmark count; the default: within 2x of
    # lama-first's wall time and 10 % of its cost on more of benchmarks/classical than gbfs), lazy
    # greedy best-first on h_FF alone, or (weighted) A*
    search: Literal["gbfs", "lama", "astar"] = "lama"
    # anytime improvement after the first forward plan (weighted A* with falling weights, bounded by
    # the best cost): CPU budget = improve x the first search's CPU time + 0.02 s; 0 = off
    improve: float = 0.0
    forward_heuristic: Literal["ff", "add", "max"] = "ff"
    # action costs as the forward heuristic sees them (FD's adapt_costs): one | plusone | normal
    cost_type: Literal["one", "plusone", "normal"] = "plusone"


_RELAXED = {"hadd": "add", "hmax": "max", "hff": "ff", "lmcut": "lmcut"}


def preimage(
    goal: Goal, action: Action, level: int | None, domain: Domain, drop: frozenset[str] = frozenset()
) -> Goal | None:
    """Regress ``goal`` through ``action`` at ``level``; ``None`` if ω destroys it.

    Atoms that an effect entails are removed, atoms whose fluent an effect
    sets to an incompatible value make the regression fail, and the kept
    preconditions (criticality > level; all if ``level`` is None) are added.
    Preconditions of predicates in ``drop`` (static facts checked at
    grounding) are left out.
    """
    rules = domain.rules
    effects = {e.key: e for e in action.effects()}
    remaining: list[Atom] = []
    for a in goal.atoms:
        e = effects.get(a.key)
        if e is None:
            remaining.append(a)
        elif not rules.rule(a.predicate).entails(e.value, a.value):
            return None
    if rules.conflicts and remaining:
        # after ω its effects hold: a remaining atom they exclude can never come true
        effs = list(effects.values())
        if contradiction(effs + remaining, rules, new=remaining) is not None:
            return None
    pre = [p for p in action.preconditions(level) if p.predicate not in drop]
    return conjoin(Goal(frozenset(remaining)), pre, rules)


_FALLBACKS_LOGGED: set[tuple[str, str, str]] = set()


def _log_fallback(domain: str, heuristic: str, why: str) -> None:
    """Say once per (domain, heuristic, reason) that the planner counts unmet atoms instead."""
    key = (domain, heuristic, why)
    if key not in _FALLBACKS_LOGGED:
        _FALLBACKS_LOGGED.add(key)
        log.info(
            "domain %s: heuristic %s falls back to counting unmet atoms: %s "
            "(PlannerConfig(lazy_relaxation=True) keeps a relaxed estimate with tests and generators)",
            domain, heuristic, why,
        )


def static_drop(domain: Domain, belief: Any, lists_facts: bool | None = None) -> frozenset[str]:
    """Static predicates checked at grounding and kept out of pre-images (when the belief lists facts)."""
    if not (isinstance(belief, ListsFacts) if lists_facts is None else lists_facts):
        return frozenset()
    return frozenset(n for n in domain.static_predicates if domain.predicates[n].test is None)


def regress_through(
    goal: Goal, actions: Sequence[Action], levels: LevelMap, domain: Domain, drop: frozenset[str]
) -> tuple[list[Goal], int | None]:
    """The pre-images ``[g0, …, gn = goal]`` of an action sequence at its levels.

    On failure, the goals regressed so far (``[g_k, …, gn]``) and the index
    of the action that destroys an atom its successors need; else ``None``.
    """
    goals = [goal]
    for i in range(len(actions) - 1, -1, -1):
        a = actions[i]
        g = preimage(goals[-1], a, levels.level(a), domain, drop)
        if g is None:
            goals.reverse()
            return goals, i
        goals.append(g)
    goals.reverse()
    return goals, None


def achieves(goal: Goal, action: Action, domain: Domain) -> bool:
    rules = domain.rules
    table = goal.by_key()
    for e in action.effects():
        a = table.get(e.key)
        if a is not None and rules.rule(a.predicate).entails(e.value, a.value):
            return True
    return False


class _Search:
    """A* over subgoals as frozensets of fact ids (:mod:`nowplan.planning.subgoals`)."""

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
        lists = isinstance(belief, ListsFacts)
        self.grounder = Grounder(domain, objects, belief, context, config.max_generator_values, lists)
        self.drop = static_drop(domain, belief, lists)
        self._holds: dict[Atom, bool] = {}
        self._fholds: dict[int, bool] = {}
        self._hv: dict[int, float] = {}
        self._costs: dict[tuple[str, tuple[Any, ...]], float] = {}
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
        self._no_relax = relax_unsupported(self.grounder, belief)
        self._can_relax = self._no_relax is None
        # with a belief that lists its facts and boolean predicates without tests, truth is membership
        self._true_ids: frozenset[int] | None = None
        if self._can_relax:
            self.true_ids()
        self._relaxers: dict[bool, LazyRelaxed] = {}  # by additive propagation: add/ff, max/lmcut
        self._ground_hadd: RelevantHadd | KernelHadd | None = None
        self._task: GroundTask | None = None
        self._ctx: tuple[frozenset[int], Goal] | None = None
        self._successors = Successors(self.table, self.grounder, levels, self.drop, self.cost)
        for name in (config.heuristic, config.shortcut_heuristic or config.heuristic):
            if name not in (*_RELAXED, "count"):
                from nowplan.errors import UsageError

                raise UsageError(f"PlannerConfig heuristic {name!r}: use hadd, hmax, hff, lmcut or count")
        self.use(config.heuristic)

    def use(self, name: str) -> None:
        """Estimate with ``name`` from now on (explorations are shared: h_max with LM-cut, h_add with h_FF)."""
        self.relaxed = self.hadd = None
        kind = _RELAXED.get(name)
        if callable(self.domain_h) or kind is None:
            return
        if self.config.lazy_relaxation or (kind != "add" and self._can_relax):
            additive = kind in ("add", "ff")
            r = self._relaxers.get(additive)
            if r is None:
                r = self._relaxers[additive] = LazyRelaxed(self._supporters, self.fholds, kind, self._context_key)
            r.kind = kind
            self.relaxed = r
        elif self._can_relax:
            if self._ground_hadd is None:
                task = ground_task(self.grounder, self.drop)
                if kernel_hadd(task, self.levels.top):  # one compiled exploration of every action
                    self._ground_hadd = KernelHadd(task, self.levels, self.true_ids())
                else:
                    self._ground_hadd = RelevantHadd(self.grounder, self.levels, self.drop, self.cost, self.true_ids())
                self._task = task
                self._successors.task = task
                self.grounder.use_task(task)  # generator-free achievers read off the ground task
            self.hadd = self._ground_hadd
        else:
            _log_fallback(self.grounder.domain.name, name, str(self._no_relax))

    def _goal_of(self, context: frozenset[int]) -> Goal:
        if self._ctx is None or self._ctx[0] is not context:
            self._ctx = (context, self.table.goal(context))
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
            if true is None or a.predicate not in self.domain.predicates:
                r = self.holds(a)
            else:  # boolean predicates without tests: a lookup in the belief's facts
                r = f in true if a.value is not False else self.table.by_key.get((a.predicate, a.args, True)) not in true
            self._fholds[f] = r
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

    def satisfied(self, fs: frozenset[int]) -> bool:
        return all(self.fholds(f) for f in fs)

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
        """A* from ``goal``; ``order`` = serialization, ``protect`` = monotonic atoms."""
        T = self.table
        fluent = T.fluent
        root = T.ids_of(goal.atoms)
        root_ok = T.consistent(root)  # else its successors are computed on Goals (see subgoals)
        order_ids = [T.id(a) for a in order] if order is not None else None
        # the atoms left out of the search while the focus is k: order[: k - 1]
        hidden = [frozenset(order_ids[: max(k - 1, 0)]) for k in range(len(order_ids) + 1)] if order_ids else []
        guard = {fluent[f]: f for f in T.ids_of(protect)}
        focus0 = len(order) if order is not None else 0
        counter = itertools.count()
        Node = tuple[frozenset[int], int]
        start: Node = (root, focus0)
        h0 = self.h(root)
        frontier: list[tuple[float, float, int, Node]] = [(self.config.weight * h0, h0, next(counter), start)]
        best_g: dict[Node, float] = {start: 0.0}
        parent: dict[Node, tuple[Node, Action] | None] = {start: None}
        closed: set[Node] = set()
        levels, drop, weight = self.levels, self.drop, self.config.weight
        hvals = self.hadd.values.__getitem__ if isinstance(self.hadd, KernelHadd) and not callable(self.domain_h) else None
        exp = 0
        regress_, forbidden, inf, push = regress, self.forbidden_first, math.inf, heapq.heappush
        while frontier:
            _, _, _, node = heapq.heappop(frontier)
            if node in closed:
                continue
            closed.add(node)
            fs, focus = node
            if order_ids is not None:
                # shift the focus down once the non-focused part already holds
                if focus > 0:
                    unmet = [f for f in fs if not self.fholds(f)]
                    while focus > 0 and hidden[focus].issuperset(unmet):
                        focus -= 1
            if self.satisfied(fs):
                return PlanStatus.SOLVED, self._path(node, parent), ""
            exp += 1
            self.expanded += 1
            if exp > max_nodes:
                return PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} nodes without a plan"
            if self.now() > self.deadline:
                return PlanStatus.TIME_LIMIT, None, f"time limit of {self.config.time_limit:g} s reached"
            gcost = best_g[node]
            skip = hidden[focus] if order_ids is not None else frozenset()
            allowed = [f for f in T.sorted(fs) if f not in skip]
            index = NodeIndex(T, fs)
            goal_of = _GoalOf(T, fs)
            legacy = not root_ok and fs == root
            tried: set[int] = set()  # by identity: the grounder makes one object per instance
            for target in allowed:
                for act, info, cost in self._successors(target, goal_of):
                    if id(act) in tried:
                        continue
                    tried.add(id(act))
                    if guard and any(guard.get(fluent[e], e) != e for e in info.all_effs):
                        continue
                    if not legacy:
                        pre = regress_(T, index, info)
                    else:
                        g = preimage(goal_of(), act, levels.level(act), self.domain, drop)
                        pre = None if g is None else T.ids_of(g.atoms)
                    if pre is None:
                        continue
                    if forbidden and act.key in forbidden and self.satisfied(pre):
                        continue  # it would be the plan's first step: learnt not to be refinable from here
                    child = (pre, focus)
                    ng = gcost + cost
                    if child in closed or ng >= best_g.get(child, inf):
                        continue
                    best_g[child] = ng
                    parent[child] = (node, act)
                    self.generated += 1
                    if hvals is not None:
                        try:  # the kernel's values: every fact valued, 0 where it holds
                            hh = sum(map(hvals, pre))
                        except IndexError:
                            hh = self.h(pre)
                    else:
                        hh = self.h(pre)
                    if hh == inf:
                        continue  # an atom of the pre-image is unreachable
                    push(frontier, (ng + weight * hh, hh, next(counter), child))
        return PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan at this level"

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


def axioms_refusal(domain: Domain) -> str:
    """Why the regression planner (and HPN) refuses a domain with derived predicates evaluated by rules, and the fix."""
    names = ", ".join(sorted(domain.derived))
    return (f"domain {domain.name} has recursive derived predicates, so its derived predicates are evaluated by "
            f"rules ({names}): the regression planner, and "
            "HPN's executive that regresses at abstract levels, cannot regress through them (a derived atom's "
            "pre-image is no conjunction of literals); plan it flat with the forward engine (nowplan plan, "
            "--engine forward; PlannerConfig(engine='forward'))")


def concrete(domain: Domain, levels: LevelMap) -> bool:
    """Every operator instance keeps all its preconditions at ``levels`` (a flat call).

    ``engine="auto"`` searches forward only then: a hierarchical call (HPN's
    abstract levels) regresses, with seed 002's shortcuts, because there the
    regression touches only the achievers the subgoal needs while the forward
    engine grounds and relaxes the whole task on every call (logistics with
    20 packages, HPN: 1.9 CPU s of planning by regression, 9.3 s forward).
    """
    return levels.top < domain.min_criticality


def context_allows_forward(context: PlanningContext | None) -> bool:
    """A domain's own estimate (``context.extras["heuristic"]``) and forbidden first steps are for the regression search."""
    return context is None or (context.extras.get("heuristic") is None and not context.extras.get("forbidden_first"))


class _GoalOf:
    """A node's subgoal as a :class:`Goal`, made on the first call (for generators)."""

    __slots__ = ("table", "fs", "goal")

    def __init__(self, table: FactTable, fs: frozenset[int]) -> None:
        self.table = table
        self.fs = fs
        self.goal: Goal | None = None

    def __call__(self) -> Goal:
        if self.goal is None:
            self.goal = self.table.goal(self.fs)
        return self.goal


def _atom_order(a: Atom) -> tuple[Any, ...]:
    return (a.predicate, a.args, a.value)


def _clock(config: PlannerConfig) -> Callable[[], float]:
    if config.clock not in ("wall", "cpu"):
        from nowplan.errors import UsageError

        raise UsageError(f"PlannerConfig.clock is {config.clock!r}; use 'wall' or 'cpu'")
    return time.process_time if config.clock == "cpu" else time.perf_counter


def plan(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap | None = None,
    config: PlannerConfig | None = None,
    context: PlanningContext | None = None,
    rng: random.Random | None = None,
) -> PlanResult:
    """Find ``[(None, g0), (ω1, g1), …, (ωn, γ)]`` with ``belief ∈ g0`` at ``levels``.

    The cyclic garbage collector is paused during the call: a call allocates many
    small acyclic objects (fact-id sets, tuples), and the collector's passes over
    the process's heap that they trigger took ~17 % of HPN's planning time on
    logistics-20; cycles made during the call are collected after it.
    """
    paused = gc.isenabled()
    if paused:
        gc.disable()
    try:
        return _plan(domain, objects, belief, goal, levels, config, context, rng)
    finally:
        if paused:
            gc.enable()


def _plan(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap | None,
    config: PlannerConfig | None,
    context: PlanningContext | None,
    rng: random.Random | None,
) -> PlanResult:
    config = config or PlannerConfig()
    levels = levels or LevelMap(domain.top_level)
    rng = rng or random.Random(config.seed)
    t_cpu = time.process_time()
    if config.engine == "forward" or (
        config.engine == "auto" and context_allows_forward(context) and concrete(domain, levels)
    ):
        from nowplan.planning.forward import plan_forward

        forward = plan_forward(domain, objects, belief, goal, levels, config)
        if forward is not None:
            return forward
    if domain.axioms:
        from nowplan.errors import ModelError

        raise ModelError(axioms_refusal(domain))
    search = _Search(domain, objects, belief, levels, config, context)
    attempts: list[str] = []
    result: tuple[PlanStatus, list[tuple[Action | None, Goal]] | None, str] = (
        PlanStatus.UNSOLVABLE,
        None,
        "",
    )
    method = "full"
    unmet = [a for a in goal.atoms if not search.fholds(search.table.id(a))]
    if config.serialization and len(goal) > 1:
        order = sorted(goal.atoms, key=_atom_order)  # the atoms' own order, compared in C
        rng.shuffle(order)
        search.use(config.shortcut_heuristic or config.heuristic)
        result = search.run(goal, config.shortcut_nodes, order=order)
        search.use(config.heuristic)
        attempts.append(f"serialization:{result[0].value}")
        method = "serialization"
    if result[0] is not PlanStatus.SOLVED and config.monotonic and len(goal) > 1 and unmet != list(goal.atoms):
        protect = frozenset(a for a in goal.atoms if search.holds(a))
        if search.now() < search.deadline:
            result = search.run(goal, config.shortcut_nodes, protect=protect)
            attempts.append(f"monotonic:{result[0].value}")
            method = "monotonic"
    if result[0] is not PlanStatus.SOLVED and search.now() < search.deadline:
        result = search.run(goal, config.max_nodes)
        attempts.append(f"full:{result[0].value}")
        method = "full"
    elif result[0] is not PlanStatus.SOLVED:
        result = (PlanStatus.TIME_LIMIT, None, f"time limit of {config.time_limit:g} s reached")
    status, steps, reason = result
    cpu = time.process_time() - t_cpu
    common = dict(
        expanded=search.expanded, generated=search.generated, cpu_time_s=cpu, attempts=tuple(attempts)
    )
    if status is not PlanStatus.SOLVED or steps is None:
        log.info("planning failed for %s: %s (%s)", goal, status.value, reason)
        return PlanResult(status, None, reason, method=method, **common)  # type: ignore[arg-type]
    p = Plan(tuple(PlanStep(a, g) for a, g in steps), levels)
    log.info("plan of %d steps by %s search (%d expanded)", len(p), method, search.expanded)
    return PlanResult(PlanStatus.SOLVED, p, "", method=method, **common)  # type: ignore[arg-type]
