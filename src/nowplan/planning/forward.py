"""Forward state-space search over an integer task, with pre-images regressed afterwards.

Where the belief lists its facts and the domain has neither generators nor
tested predicates, the planner may search forward from the belief instead
of backward from the goal (issue 19): the task is grounded once per problem
(:mod:`nowplan.planning.task`), the search is

* ``gbfs``: greedy best-first search with lazy evaluation and preferred
  operators in a second, boosted open list (LAMA's first iteration with h_FF
  alone; FD's ``lazy_greedy([ff], preferred=[ff])``), or
* ``astar``: eager weighted A* (``f = g + w h``; with ``w = 1`` and h_max it
  is optimal),

and the plan's pre-images come from regressing the goal through the found
action sequence at each action's level, exactly as the regression planner
computes them (:func:`regress_actions`), so the executive can monitor them.

When the compiled kernel is built (:mod:`nowplan.planning.native`), the
whole lazy GBFS and LAMA loops run in C and A* uses its heuristic and
successor generator; the Python code below is the reference and gives the same plans
and counters.
"""

from __future__ import annotations

import heapq
import itertools
import logging
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Literal

from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.axioms import evaluator
from nowplan.planning.forward_generators import NotEnumerable
from nowplan.planning.generators_run import misses_hint
from nowplan.planning.hff import CostType, Kind, RelaxedHeuristic
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.postprocess import eliminate_actions
from nowplan.planning.task import Task, build_task, forward_unsupported

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel
    from nowplan.planning.config import PlannerConfig

log = logging.getLogger(__name__)

Search = Literal["gbfs", "lama", "astar"]
BOOST = 1000  # priority given to the preferred-operator queue on progress (FD's default)
# work units (about h_FF evaluations, anytime.py) the anytime improvement always gets (with ``improve``
# > 0), and ``improve`` x the first search's expansions (one evaluation each, lazily) more.  On
# benchmarks/classical's 65 instances 32,000 spends 0.66x the CPU of the 0.02 s + 1x first-search CPU
# budget this replaced, for plans as cheap (benchmarks/results/anytime_units/)
IMPROVE_BASE = 32_000


@dataclass
class ForwardResult:
    status: PlanStatus
    actions: list[Action] | None
    reason: str
    expanded: int = 0
    generated: int = 0
    evaluated: int = 0
    regrouped: bool = False  # the plan's order is regroup's (planning/regroup.py), not the search's


class _Successors:
    """A successor generator: each action is filed under one precondition (the rarest).

    ``native``: the compiled kernel's generator runs instead (same result).
    """

    def __init__(self, task: Task, native: Kernel | None = None) -> None:
        self.native = native
        self.pre = task.pre
        self.always = list(task.no_pre)
        self.by_fact: dict[int, list[int]] = {}
        for a, p in enumerate(task.pre):
            if p:
                trigger = min(p, key=lambda f: len(task.by_pre.get(f, ())))
                self.by_fact.setdefault(trigger, []).append(a)

    def __call__(self, state: frozenset[int]) -> list[int]:
        if self.native is not None:
            return self.native.applicable(state)
        pre = self.pre
        out = list(self.always)
        by_fact = self.by_fact
        for f in state:
            for a in by_fact.get(f, ()):
                if all(p in state for p in pre[a]):
                    out.append(a)
        out.sort()
        return out


def search(
    task: Task,
    *,
    method: Search = "gbfs",
    heuristic: Kind = "ff",
    cost_type: CostType = "plusone",
    weight: float = 1.0,
    max_nodes: int = 500_000,
    out_of_time: Callable[[], bool] = lambda: False,
) -> ForwardResult:
    """Search ``task`` forward; the plan is a list of action ids mapped to actions."""
    if task.unsolvable:
        return ForwardResult(PlanStatus.UNSOLVABLE, None, task.unsolvable)
    if method == "lama":
        from nowplan.planning.lama import lama_search

        return lama_search(task, cost_type=cost_type, max_nodes=max_nodes, out_of_time=out_of_time)
    h = RelaxedHeuristic(task, heuristic, cost_type)
    if method == "gbfs" and h.native is not None:
        res = _native_gbfs(task, h.native, max_nodes, out_of_time)
        h.evaluations += res.evaluated
        return res
    succ = _Successors(task, h.native)
    if method == "gbfs":
        res = _lazy_gbfs(task, h, succ, max_nodes, out_of_time)
    else:
        res = _astar(task, h, succ, weight, max_nodes, out_of_time)
    res.evaluated = h.evaluations
    return res


def _goal_reached(task: Task, state: frozenset[int]) -> bool:
    return all(g in state for g in task.goal)


def _apply(task: Task, state: frozenset[int], a: int) -> frozenset[int]:
    """The successor of ``state`` by action ``a`` (its derived facts recomputed when the task has axioms)."""
    nxt = state.difference(task.dele[a]).union(task.add[a])
    if task.axioms:
        ev = evaluator(task)
        assert ev is not None
        return ev.evaluate(nxt)
    return nxt


def _path(task: Task, parent: Mapping[frozenset[int], tuple[frozenset[int], int] | None],
          state: frozenset[int]) -> list[Action]:
    acts: list[Action] = []
    cur = parent[state]
    while cur is not None:
        prev, a = cur
        acts.append(task.actions[a])
        cur = parent[prev]
    acts.reverse()
    return acts


def _native_gbfs(task: Task, kernel: Kernel, max_nodes: int, out_of_time: Callable[[], bool]) -> ForwardResult:
    """:func:`_lazy_gbfs` in the compiled kernel: the same plan and counters."""
    return native_result(task, kernel.gbfs(task.init, max_nodes, out_of_time, BOOST), max_nodes)


def native_result(task: Task, out: tuple[int, list[int] | None, int, int, int], max_nodes: int) -> ForwardResult:
    """A kernel search's ``(status, plan ids, expanded, generated, evaluated)`` as a :class:`ForwardResult`."""
    from nowplan.planning import _kernel as k

    status, plan, expanded, generated, evaluated = out
    if status == k.SOLVED and plan is not None:
        res = ForwardResult(PlanStatus.SOLVED, [task.actions[a] for a in plan], "", expanded, generated)
    elif status == k.DEAD_INIT:
        res = ForwardResult(PlanStatus.UNSOLVABLE, None, "the goal is unreachable even ignoring deletes")
    elif status == k.NODE_LIMIT:
        res = ForwardResult(PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} states without a plan",
                            expanded, generated)
    elif status == k.TIME_LIMIT:
        res = ForwardResult(PlanStatus.TIME_LIMIT, None, "time limit reached", expanded, generated)
    else:
        res = ForwardResult(PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan", expanded, generated)
    res.evaluated = evaluated
    return res


def _lazy_gbfs(task: Task, h: RelaxedHeuristic, succ: _Successors, max_nodes: int,
               out_of_time: Callable[[], bool]) -> ForwardResult:
    init = task.init
    h0, pref0 = h.evaluate(init)
    if h0 == math.inf:
        return ForwardResult(PlanStatus.UNSOLVABLE, None, "the goal is unreachable even ignoring deletes")
    parent: dict[frozenset[int], tuple[frozenset[int], int] | None] = {init: None}
    if _goal_reached(task, init):
        return ForwardResult(PlanStatus.SOLVED, [], "", 0, 0)
    tick = itertools.count()
    regular: list[tuple[float, int, frozenset[int], int]] = []
    preferred: list[tuple[float, int, frozenset[int], int]] = []
    priority = [0, 0]  # regular, preferred: the queue with the lower number is served next
    best = h0
    expanded = generated = 0

    def expand(state: frozenset[int], hv: float, pref: list[int]) -> None:
        nonlocal generated
        prefset = set(pref)
        for a in succ(state):
            generated += 1
            entry = (hv, next(tick), state, a)
            heapq.heappush(regular, entry)
            if a in prefset:
                heapq.heappush(preferred, entry)

    expand(init, h0, pref0)
    while regular or preferred:
        if preferred and (not regular or priority[1] <= priority[0]):
            _, _, parent_state, a = heapq.heappop(preferred)
            priority[1] += 1
        else:
            _, _, parent_state, a = heapq.heappop(regular)
            priority[0] += 1
        state = _apply(task, parent_state, a)
        if state in parent:
            continue
        parent[state] = (parent_state, a)
        expanded += 1
        if expanded > max_nodes:
            return ForwardResult(PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} states without a plan",
                                 expanded, generated)
        if out_of_time():
            return ForwardResult(PlanStatus.TIME_LIMIT, None, "time limit reached", expanded, generated)
        if _goal_reached(task, state):
            return ForwardResult(PlanStatus.SOLVED, _path(task, parent, state), "", expanded, generated)
        hv, pref = h.evaluate(state)
        if hv == math.inf:
            continue
        if hv < best:
            best = hv
            priority[1] -= BOOST
        expand(state, hv, pref)
    return ForwardResult(PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan", expanded, generated)


def _astar(task: Task, h: RelaxedHeuristic, succ: _Successors, weight: float, max_nodes: int,
           out_of_time: Callable[[], bool]) -> ForwardResult:
    init = task.init
    h0, _ = h.evaluate(init)
    if h0 == math.inf:
        return ForwardResult(PlanStatus.UNSOLVABLE, None, "the goal is unreachable even ignoring deletes")
    tick = itertools.count()
    best_g: dict[frozenset[int], float] = {init: 0.0}
    parent: dict[frozenset[int], tuple[frozenset[int], int] | None] = {init: None}
    hcache: dict[frozenset[int], float] = {init: h0}
    frontier: list[tuple[float, float, int, frozenset[int]]] = [(weight * h0, h0, next(tick), init)]
    closed: set[frozenset[int]] = set()
    expanded = generated = 0
    cost = task.cost
    while frontier:
        _, _, _, state = heapq.heappop(frontier)
        if state in closed:
            continue
        if _goal_reached(task, state):
            return ForwardResult(PlanStatus.SOLVED, _path(task, parent, state), "", expanded, generated)
        closed.add(state)
        expanded += 1
        if expanded > max_nodes:
            return ForwardResult(PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} states without a plan",
                                 expanded, generated)
        if out_of_time():
            return ForwardResult(PlanStatus.TIME_LIMIT, None, "time limit reached", expanded, generated)
        g = best_g[state]
        for a in succ(state):
            nxt = _apply(task, state, a)
            ng = g + cost[a]
            if ng >= best_g.get(nxt, math.inf):
                continue
            best_g[nxt] = ng
            parent[nxt] = (state, a)
            closed.discard(nxt)  # reopened with a cheaper path
            generated += 1
            hv = hcache.get(nxt)
            if hv is None:
                hv = hcache[nxt] = h.evaluate(nxt)[0]
            if hv == math.inf:
                continue
            heapq.heappush(frontier, (ng + weight * hv, hv, next(tick), nxt))
    return ForwardResult(PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan", expanded, generated)


def regress_actions(
    domain: Domain, belief: Any, goal: Goal, actions: Sequence[Action], levels: LevelMap
) -> list[tuple[Action | None, Goal]] | None:
    """``[(None, g0), (a1, g1), …, (an, goal)]`` by regression at each action's level.

    ``None`` if an action destroys a pre-image atom or the belief does not
    satisfy ``g0`` (the sequence is then not a plan at these levels).
    """
    from nowplan.planning.preimage import static_drop
    from nowplan.planning.preimage_chain import regress_chain

    drop = static_drop(domain, belief)
    if domain.axioms:
        found = _regress_base(domain, goal, actions, levels, drop)
        if found is None:
            return None
        goals = found
    else:
        goals, failed = regress_chain(goal, actions, levels, domain, drop)
        if failed is not None:
            return None
    if not domain.satisfies(belief, [a for a in goals[0].atoms if a.predicate not in domain.derived]):
        return None
    return [(None, goals[0]), *zip(actions, goals[1:], strict=True)]


def _regress_base(domain: Domain, goal: Goal, actions: Sequence[Action], levels: LevelMap,
                  drop: frozenset[str]) -> list[Goal] | None:
    """Pre-images ``[g0, …, gn = goal]`` where derived literals are kept only where they are needed.

    No action adds or deletes a derived atom, yet an action may change its
    truth; its pre-image through the action is a condition on the base facts
    that is no conjunction of literals.  So each step regresses the base
    literals as usual and adds the action's own conditions; a derived literal
    of ``g_{i+1}`` is kept in ``g_i`` where no effect of action ``i + 1`` can
    change it (none matches the basic atoms its rules can read,
    :class:`~nowplan.planning.derived_state.DerivedCones`: a delivered package
    stays delivered while other packages move), else dropped.  The forward
    search checked the dropped ones in the states it went through; these are
    not the weakest pre-images, and where a derived literal was dropped not
    sufficient ones either (the executive checks the goal itself at the end).
    ``None`` if an action destroys a base literal needed later.
    """
    from nowplan.core.atoms import Goal as GoalT, conjoin
    from nowplan.planning.derived_state import derived_cones
    from nowplan.planning.preimage import preimage

    cones = derived_cones(domain)
    goals = [goal]
    for i in range(len(actions) - 1, -1, -1):
        after = goals[-1].atoms
        base = GoalT.of([a for a in after if a.predicate not in domain.derived], domain.rules)
        g = preimage(base, actions[i], levels.level(actions[i]), domain, drop)
        if g is None:
            return None
        effects = list(actions[i].effects())
        kept = [a for a in after if a.predicate in domain.derived and not cones.touches(effects, a)]
        if kept:
            g = conjoin(g, kept, domain.rules) or g  # (no contradiction where the search's states held both)
        goals.append(g)
    goals.reverse()
    return goals


def forward_plan(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap,
    cost_of: Callable[[Action], float],
    *,
    method: Search = "gbfs",
    heuristic: Kind = "ff",
    cost_type: CostType = "plusone",
    weight: float = 1.0,
    max_nodes: int = 500_000,
    out_of_time: Callable[[], bool] = lambda: False,
    improve: float = 0.0,
    cache_costs: bool = False,
    relevant_to: Goal | None = None,
    hidden_costs: bool = False,
    generator_values: int = 8,
    regroup: bool = False,
) -> tuple[ForwardResult, list[tuple[Action | None, Goal]] | None]:
    """Ground, search and regress: the result and the plan's steps (``None`` unless solved).

    ``cache_costs``: ``cost_of`` is ``Action.cost`` in ``belief``; ``relevant_to``: a goal whose
    relevant operators are grounded too (see :func:`build_task`); ``hidden_costs``: abstract actions
    cost an estimate of their hidden preconditions too (:mod:`nowplan.planning.hidden_costs`);
    ``regroup``: the plan is reordered by what its steps hide before it is regressed
    (:mod:`nowplan.planning.regroup`; the search's order where the new one does not regress).
    """
    task = build_task(domain, objects, belief, goal, levels, cost_of, cache_costs=cache_costs,
                      relevant_to=relevant_to, hidden_costs=hidden_costs, generator_values=generator_values)
    res = search(task, method=method, heuristic=heuristic, cost_type=cost_type, weight=weight,
                 max_nodes=max_nodes, out_of_time=out_of_time)
    if res.status is not PlanStatus.SOLVED or res.actions is None:
        misses = task.memo.get("generator misses")
        if misses:  # generators whose proposals were all skipped: named, as the regression search does
            res.reason += misses_hint(misses)
        return res, None
    pos: dict[Any, int] = task.memo.get("position") or {act.key: i for i, act in enumerate(task.actions)}
    found = eliminate_actions(task, [pos[a.key] for a in res.actions])
    if improve > 0 and found:
        from nowplan.planning.anytime import improve as improve_plan

        budget = round(improve * res.expanded) + IMPROVE_BASE
        branching = max(1, round(res.generated / max(1, res.expanded)))
        found = eliminate_actions(task, improve_plan(task, found, budget, cost_type, out_of_time,
                                                     branching=branching))
    res.actions = [task.actions[i] for i in found]
    steps = None
    if regroup:
        from nowplan.planning.regroup import regroup as regrouped

        steps = regrouped(domain, belief, goal, res.actions, levels)  # (regressed: instead of the search's order)
        if steps is not None:
            res.actions, res.regrouped = [a for a, _ in steps[1:] if a is not None], True
    if steps is None:
        steps = regress_actions(domain, belief, goal, res.actions, levels)
    if steps is None:
        log.warning("the forward plan for %s does not regress into pre-images at its levels", goal)
    return res, steps


def plan_forward(
    domain: Domain,
    objects: Mapping[str, str | None],
    belief: Any,
    goal: Goal,
    levels: LevelMap,
    config: PlannerConfig,
) -> PlanResult | None:
    """The regression planner's entry point, searching forward; ``None``: use the regression search.

    ``None`` when forward search does not apply (``engine="auto"`` on a domain
    with generators or tests, or a belief that does not list its facts) or,
    in the rare case, when the found plan does not regress into pre-images at
    its levels (then the regression search answers instead).
    """
    from nowplan.errors import UsageError
    from nowplan.planning.config import _clock

    why = forward_unsupported(domain, belief) or domain.facts.derived.get("forward not enumerable")
    if why is not None:
        if config.engine == "forward":
            raise UsageError(f"the forward engine cannot plan here: {why}; use engine='regression'")
        said = domain.facts.derived
        if said.get("forward_unsupported") != why:  # once per domain and reason at INFO (every call asks)
            said["forward_unsupported"] = why
            log.info("forward search does not apply (%s): the regression search plans instead", why)
        else:
            log.debug("forward search does not apply (%s): regression search", why)
        return None
    now = _clock(config)
    deadline = now() + config.time_limit
    t_cpu = time.process_time()
    costs: dict[tuple[str, tuple[Any, ...]], float] = {}

    def cost_of(act: Action) -> float:
        c = costs.get(act.key)
        if c is None:
            c = costs[act.key] = act.cost(belief)
        return c

    try:
        res, steps = forward_plan(
            domain, objects, belief, goal, levels, cost_of,
            method=config.search, heuristic=config.forward_heuristic, cost_type=config.cost_type,
            weight=config.weight,
            max_nodes=config.max_nodes if config.forward_max_nodes is None else config.forward_max_nodes,
            out_of_time=lambda: now() > deadline,
            improve=config.improve, cache_costs=True, relevant_to=config.relevant_to,
            hidden_costs=config.hidden_costs, generator_values=config.max_generator_values,
            regroup=config.regroup,
        )
    except NotEnumerable as e:  # a generator's values are not objects: the regression search grounds them
        if config.engine == "forward":
            raise UsageError(f"the forward engine cannot plan here: {e}; use engine='regression'") from None
        domain.facts.derived["forward not enumerable"] = str(e)  # the later calls do not try again
        log.info("forward search does not apply (%s): the regression search plans instead", e)
        return None
    method = f"forward:{config.search}" + ("+regroup" if res.regrouped else "")
    common: dict[str, Any] = dict(expanded=res.expanded, generated=res.generated, method=method,
                                  attempts=(f"{method}:{res.status.value}",))
    if res.status is PlanStatus.SOLVED:
        if steps is None:
            return None
        p = Plan(tuple(PlanStep(a, g) for a, g in steps), levels)
        log.info("plan of %d steps by %s (%d expanded)", len(p), method, res.expanded)
        return PlanResult(PlanStatus.SOLVED, p, "", cpu_time_s=time.process_time() - t_cpu, **common)
    reason = res.reason
    if res.status is PlanStatus.TIME_LIMIT:
        reason = f"time limit of {config.time_limit:g} s reached"
    log.info("planning failed for %s: %s (%s)", goal, res.status.value, reason)
    return PlanResult(res.status, None, reason, cpu_time_s=time.process_time() - t_cpu, **common)
