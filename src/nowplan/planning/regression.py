"""Regression (pre-image backchaining) A* over an abstraction level.

``plan(...)`` searches backwards from the goal γ: a node is a subgoal G (a
conjunction), a successor is the pre-image of G under an operator instance
ω at ω's level (seed 002 II-A/B), and the search stops at a subgoal the
current belief satisfies.  HPN's shortcuts (seed 002 V-B) run first when
switched on: a random serialization of the goal's conjuncts, then a
monotonic plan (never undoing a goal fluent that already holds), then full
backward search.  Limits end the search with a typed :class:`PlanResult`.

This module holds the entry point and the engine choice; the settings are
in :mod:`nowplan.planning.config`, the pre-images of goals in
:mod:`nowplan.planning.preimage`, the search in
:mod:`nowplan.planning.regression_search`.  The names other modules import
from here are re-exported (``__all__``).
"""

from __future__ import annotations

import gc
import logging
import random
import time
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.generators_run import misses_hint
from nowplan.planning.config import PlannerConfig
from nowplan.planning.forward import plan_forward
from nowplan.planning.task import forward_unsupported
from nowplan.planning.context import PlanningContext
from nowplan.planning.plan import Plan, PlanResult, PlanStatus, PlanStep
from nowplan.planning.preimage import achieves, preimage, regress_through, static_drop

__all__ = [
    "PlannerConfig",
    "achieves",
    "axioms_refusal",
    "concrete",
    "context_allows_forward",
    "plan",
    "preimage",
    "regress_through",
    "static_drop",
]

log = logging.getLogger(__name__)
SHORTCUT_SHARE = 0.25  # of a call's time limit, for the shortcuts when the forward search may follow them


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



def forward_fallback_applies(domain: Domain, levels: LevelMap, config: PlannerConfig,
                             context: PlanningContext | None) -> bool:
    """Whether a hierarchical call whose shortcuts failed tries the forward search before the full
    regression: ``engine="auto"``, an abstract level (a concrete one searched forward already) and
    a context the forward search may serve."""
    return config.engine == "auto" and not concrete(domain, levels) and context_allows_forward(context)


def _forward_fallback(domain: Domain, objects: Mapping[str, str | None], belief: Any, goal: Goal,
                      levels: LevelMap, config: PlannerConfig, left: float) -> PlanResult | None:
    """The forward search at ``levels`` in half the time left (``None``: it does not apply here).

    Seed 002's shortcuts find most hierarchical plans by regression in a few nodes; when both fail,
    the full regression search can be hopeless where a forward search is quick: a goal that asks
    for boxes dug out of stacks has subgoals that grow with every box moved aside and a branching
    of every place a box may be put (the warehouse held-out domain, issue 14: 2,000 regression
    nodes in ~9 CPU s without a plan, the forward search at the same level in 8 expansions).
    """
    return plan_forward(domain, objects, belief, goal, levels, replace(config, time_limit=max(left / 2, 0.01)))


def _atom_order(a: Atom) -> tuple[Any, ...]:
    return (a.predicate, a.args, a.value)



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

    A regression-engine plan is trimmed of steps the rest does not need (``config.prune``,
    :mod:`nowplan.planning.prune`) and, with ``config.regroup``, reordered by what its steps hide
    (:mod:`nowplan.planning.regroup`; the forward engine does both itself); the method then ends in
    ``+pruned`` / ``+regroup``.
    """
    paused = gc.isenabled()
    if paused:
        gc.disable()
    try:
        result = _plan(domain, objects, belief, goal, levels, config, context, rng)
        if result.plan is not None and not result.method.startswith("forward:"):  # (forward: its own)
            if config is None or config.prune:
                result = _rewritten(domain, belief, result, "pruned")
            if config is not None and config.regroup:
                result = _rewritten(domain, belief, result, "regroup")
        return result
    finally:
        if paused:
            gc.enable()


def _rewritten(domain: Domain, belief: Any, result: PlanResult, suffix: str) -> PlanResult:
    """``result`` with its plan pruned (``suffix`` "pruned", :mod:`nowplan.planning.prune`) or
    regrouped ("regroup", :mod:`nowplan.planning.regroup`) where that changes it."""
    from nowplan.planning.prune import prune
    from nowplan.planning.regroup import regroup

    assert result.plan is not None
    t = time.process_time()
    p = result.plan
    if suffix == "pruned":
        steps = prune(domain, belief, p.goal, p.actions, p.levels, lambda a: a.cost(belief))
    else:
        steps = regroup(domain, belief, p.goal, p.actions, p.levels)
    cpu = result.cpu_time_s + time.process_time() - t
    if steps is None:
        return replace(result, cpu_time_s=cpu)
    plan = Plan(tuple(PlanStep(a, g) for a, g in steps), p.levels)
    return replace(result, plan=plan, method=f"{result.method}+{suffix}", cpu_time_s=cpu)


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
        # the domain's proof of no plan, as the regression path asks it: a forward search would only
        # prove it again by exhausting the space (or run out of nodes first)
        dead = domain.dead_end(goal, belief, levels, objects) if domain.dead_end is not None else None
        if dead is not None:
            return PlanResult(PlanStatus.UNSOLVABLE, None, dead, method="dead_end",
                              cpu_time_s=time.process_time() - t_cpu, attempts=("dead_end:unsolvable",))
        forward = plan_forward(domain, objects, belief, goal, levels, config)
        if forward is not None:
            return forward
    if domain.axioms:
        from nowplan.errors import ModelError

        raise ModelError(axioms_refusal(domain))
    # imported at the first regression search: a forward-only run (nowplan plan, a PDDL
    # --criticality auto run) never loads the regression search's ~15 modules
    from nowplan.planning.regression_search import _Search

    search = _Search(domain, objects, belief, levels, config, context)
    attempts: list[str] = []
    result: tuple[PlanStatus, list[tuple[Action | None, Goal]] | None, str] = (
        PlanStatus.UNSOLVABLE,
        None,
        "",
    )
    method = "full"
    unmet = [a for a in goal.atoms if not search.fholds(search.table.id(a))]

    def budget(nodes: int) -> int:
        """An attempt's expansions: its own budget, within what is left of ``call_nodes``."""
        return nodes if config.call_nodes <= 0 else min(nodes, config.call_nodes - search.expanded)

    # a hierarchical call that may fall back on the forward search keeps most of its time for it:
    # the shortcuts, meant to be quick, get a quarter (they ran into the call's whole time limit);
    # a goal of one atom, which has no shortcuts, gets a full search within their budget instead
    fallback = forward_fallback_applies(domain, levels, config, context) and forward_unsupported(domain, belief) is None
    deadline = search.deadline
    if fallback:
        search.deadline = min(deadline, search.now() + config.time_limit * SHORTCUT_SHARE)
    order: list[Atom] | None = None
    if config.serialization and len(goal) > 1:
        order = sorted(goal.atoms, key=_atom_order)  # the atoms' own order, compared in C
        rng.shuffle(order)
    # the domain's proof of no plan comes after the serialization's draw, so a call it answers
    # leaves the random stream where the search would have left it
    dead = domain.dead_end(goal, belief, levels, objects) if domain.dead_end is not None else None
    if dead is not None:
        result = (PlanStatus.UNSOLVABLE, None, dead)
        attempts.append("dead_end:unsolvable")
        method = "dead_end"
    elif order is not None:
        search.use(config.shortcut_heuristic or config.heuristic)
        result = search.run(goal, budget(config.shortcut_nodes), order=order)
        search.use(config.heuristic)
        attempts.append(f"serialization:{result[0].value}")
        method = "serialization"
    spent = config.call_nodes > 0 and search.expanded >= config.call_nodes
    if (dead is None and result[0] is not PlanStatus.SOLVED and config.monotonic and len(goal) > 1 and unmet != list(goal.atoms)
            and not spent):
        protect = frozenset(a for a in goal.atoms if search.holds(a))
        if search.now() < search.deadline:
            result = search.run(goal, budget(config.shortcut_nodes), protect=protect)
            attempts.append(f"monotonic:{result[0].value}")
            method = "monotonic"
    spent = config.call_nodes > 0 and search.expanded >= config.call_nodes
    proved = False  # a bounded full search that ran out of subgoals: no plan at these levels
    if fallback and dead is None and not attempts and not spent and search.now() < search.deadline:
        # no shortcut ran (a goal of one atom): a full search within the shortcuts' budget stands in
        result = search.run(goal, budget(config.shortcut_nodes))
        attempts.append(f"bounded:{result[0].value}")
        proved = result[0] is PlanStatus.UNSOLVABLE
    spent = config.call_nodes > 0 and search.expanded >= config.call_nodes
    search.deadline = deadline
    if (dead is None and result[0] is not PlanStatus.SOLVED and attempts and not spent and fallback
            and not proved and search.now() < search.deadline):
        forward = _forward_fallback(domain, objects, belief, goal, levels, config, search.deadline - search.now())
        if forward is not None:
            attempts.append(forward.attempts[-1] if forward.attempts else "forward")
            if forward.solved:
                expanded = forward.expanded + search.expanded
                search.release()
                return replace(forward, attempts=tuple(attempts), expanded=expanded,
                               cpu_time_s=time.process_time() - t_cpu)
    if dead is not None or proved:
        pass
    elif result[0] is not PlanStatus.SOLVED and spent:
        result = (PlanStatus.NODE_LIMIT, None,
                  f"expanded {search.expanded} nodes over the call's attempts without a plan (call_nodes)")
    elif result[0] is not PlanStatus.SOLVED and search.now() < search.deadline:
        result = search.run(goal, budget(config.max_nodes))
        attempts.append(f"full:{result[0].value}")
        method = "full"
        if (result[0] is PlanStatus.NODE_LIMIT and config.retry_weight > config.weight and search.now() < search.deadline
                and not (config.call_nodes > 0 and search.expanded >= config.call_nodes)):
            search.config = replace(config, weight=config.retry_weight)  # (read by both search loops)
            result = search.run(goal, budget(config.max_nodes))
            search.config = config
            attempts.append(f"weighted:{result[0].value}")
            method = "weighted"
    elif result[0] is not PlanStatus.SOLVED:
        result = (PlanStatus.TIME_LIMIT, None, f"time limit of {config.time_limit:g} s reached")
    status, steps, reason = result
    cpu = time.process_time() - t_cpu
    common = dict(
        expanded=search.expanded, generated=search.generated, cpu_time_s=cpu, attempts=tuple(attempts)
    )
    misses = search.grounder.misses
    search.release()  # freed now, not by the collector (see _Search.release)
    if status is not PlanStatus.SOLVED or steps is None:
        reason += misses_hint(misses)
        log.info("planning failed for %s: %s (%s)", goal, status.value, reason)
        return PlanResult(status, None, reason, method=method, **common)  # type: ignore[arg-type]
    p = Plan(tuple(PlanStep(a, g) for a, g in steps), levels)
    log.info("plan of %d steps by %s search (%d expanded)", len(p), method, common["expanded"])
    return PlanResult(PlanStatus.SOLVED, p, "", method=method, **common)  # type: ignore[arg-type]
