"""A problem's automatic hierarchy: type sets checked against its objects, and the executive's set-up.

:mod:`nowplan.planning.abstraction` derives Knoblock's hierarchy from the domain alone; this module
applies it to one problem: the level of a ground atom (:func:`ground_level`), the goal's stages
(:func:`goal_stages`), the hierarchy that merges type sets sharing one of the problem's objects
(:func:`problem_hierarchy`), and what ``nowplan run --criticality auto`` runs before acting
(:func:`prepare_problem`: criticalities, reachability statics, the dead-end test, the stages).
"""

from __future__ import annotations

import gc
import logging
from collections.abc import Mapping
from dataclasses import replace

from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Problem
from nowplan.core.operators import Action, Precondition
from nowplan.core.state import State
from nowplan.planning.abstraction import (
    Hierarchy,
    LiteralClass,
    apply_hierarchy,
    derive_hierarchy,
    merged_hierarchy,
)
from nowplan.planning.type_predicates import object_sets, shared_objects

log = logging.getLogger(__name__)

def ground_level(problem: Problem, hierarchy: Hierarchy, atom: Atom,
                 sets: Mapping[str, frozenset[str]] | None = None) -> int | None:
    """The level of a ground atom of ``problem`` (``None``: static, or in no operator's classes);
    ``sets``: each type set's objects (made here if not given)."""
    domain = problem.domain
    if hierarchy.type_sets and sets is None:
        sets = object_sets(problem, (t for c in hierarchy.members for t in c.types))
    if atom.predicate in hierarchy.static:
        return None
    if atom.predicate in hierarchy.derived:
        return hierarchy.derived[atom.predicate]
    objs = problem.all_objects
    types = [objs.get(a) if isinstance(a, str) else None for a in atom.args]
    for c, rep in hierarchy.members.items():
        if c.predicate != atom.predicate or rep not in hierarchy.levels:
            continue
        if all(not ct or (a in sets[ct] if sets is not None and ct in sets else
                          t is not None and t in domain.subtypes(ct))
               for ct, t, a in zip(c.types, types, atom.args, strict=True)):
            return hierarchy.levels[rep]
    return None


def goal_stages(problem: Problem, hierarchy: Hierarchy) -> tuple[Goal, ...]:
    """The goal's literals of levels ``>= top``, then ``>= top - 1``, ... (each a :class:`Goal`).

    HPN keeps the whole goal at every level, so without stages a top-level
    plan's pre-images carry the goal's concrete literals (where each truck
    and driver must end up) into every refinement, which then moves them back
    and forth.  Achieving the abstract literals first (ALPINE plans each level
    for that level's literals) leaves the concrete ones to the last plan.
    The full goal is not included (it is the problem's goal); stages that
    add nothing are left out.
    """
    atoms = list(problem.goal.atoms)
    sets = object_sets(problem, (t for c in hierarchy.members for t in c.types)) if hierarchy.type_sets else None
    levels = {a: ground_level(problem, hierarchy, a, sets) for a in atoms}
    stages: list[Goal] = []
    prev: frozenset[Atom] = frozenset()
    for k in range(hierarchy.top, 0, -1):
        part = frozenset(a for a in atoms if levels[a] is None or levels[a] >= k)  # type: ignore[operator]
        if part and part != prev and len(part) < len(atoms):
            stages.append(Goal.of(sorted(part), problem.domain.rules))
        prev = part
    return tuple(stages)


def _split_pairs(hierarchy: Hierarchy) -> list[tuple[tuple[str, ...], tuple[str, ...]]]:
    """The argument types of every two classes of one predicate that the hierarchy keeps apart."""
    by_pred: dict[str, list[LiteralClass]] = {}
    for c in hierarchy.members:
        by_pred.setdefault(c.predicate, []).append(c)
    return [(x.types, y.types) for cs in by_pred.values() for i, x in enumerate(cs) for y in cs[i + 1:]
            if hierarchy.members[x] != hierarchy.members[y]]


def problem_hierarchy(problem: Problem) -> Hierarchy:
    """The automatic hierarchy for ``problem``: the domain's, unless two of its type sets (taken as
    disjoint) share one of the problem's objects where a predicate's classes are kept apart; then
    the one whose classes merge wherever their type sets share an object of the problem."""
    hierarchy = derive_hierarchy(problem.domain)
    if not hierarchy.type_sets:
        return hierarchy
    shared = shared_objects(problem, _split_pairs(hierarchy))
    if shared is None:
        return hierarchy
    log.info("%s: type sets merged where they share objects: %s", problem.name, shared)
    sets = object_sets(problem, (t for c in hierarchy.members for t in c.types))
    return merged_hierarchy(problem.domain, lambda a, b: bool(sets[a] & sets[b]))


def checked_type_sets(problem: Problem) -> Problem:
    """``problem`` whose domain has the criticalities of :func:`problem_hierarchy` (``load_pddl(...,
    "auto")``): unchanged unless type sets of the domain's hierarchy share objects of the problem."""
    hierarchy = problem_hierarchy(problem)
    if hierarchy is derive_hierarchy(problem.domain):  # the domain's own (kept: the same object)
        return problem
    return replace(problem, domain=apply_hierarchy(problem.domain, hierarchy))


def prepare_problem(problem: Problem) -> Problem:
    """What ``nowplan run --criticality auto`` runs: the automatic criticalities (if the domain
    has none yet), reachability statics (:mod:`nowplan.planning.reach_statics`) and the goal
    stages (:func:`goal_stages`).

    The cyclic garbage collector is paused meanwhile, as during a planner call
    (:func:`nowplan.planning.regression.plan`): the concrete grounding allocates many small
    acyclic objects, and the collector's passes over the heap they trigger are no part of the work.
    """
    paused = gc.isenabled()
    if paused:
        gc.disable()
    try:
        return _prepare(problem)
    finally:
        if paused:
            gc.enable()


def _prepare(problem: Problem) -> Problem:
    from nowplan.planning.dead_ends import irreversible_step
    from nowplan.planning.reach_statics import add_reachability_statics
    from nowplan.planning.task_grounding import cached_grounding, share_concrete

    domain = problem.domain
    hierarchy = problem_hierarchy(problem)
    if hierarchy.top == 0:
        return problem
    if domain.top_level <= 0:
        problem = replace(problem, domain=apply_hierarchy(domain, hierarchy))
    top = hierarchy.top
    below = {op.name: (k := hierarchy.effect_level(domain, op)) is not None and k < top for op in domain.operators}

    def below_top(act: Action) -> bool:
        return below.get(act.operator.name, False)

    # the reachability statics first: where their grounding is shared with every level (the exact case),
    # the dead-end test reads that grounding too, and the achievers index it makes there is the one
    # the executive's direct refinements read (acting/refine.py), made once per run
    prepared = add_reachability_statics(problem)
    shared = prepared is not problem and isinstance(prepared.init, State) and cached_grounding(
        prepared.domain, prepared.objects, prepared.init, -1) is not None
    dead = irreversible_step(prepared if shared else problem, below_top)
    if dead is not None:
        log.warning("%s: the automatic hierarchy is not used, planning flat: %s (an abstract plan "
                    "cannot see it, and executing its first steps could leave no plan)", problem.name, dead)
        flat = tuple(replace(op, preconditions=tuple(Precondition(p.atom, 1) for p in op.preconditions))
                     for op in problem.domain.operators)
        flat_problem = replace(problem, domain=replace(problem.domain, operators=flat))
        concrete = cached_grounding(problem.domain, problem.objects, problem.init, -1)
        if concrete is not None:  # the dead-end test's grounding: every level of the flat domain has it
            share_concrete(concrete, flat_problem.domain, problem.objects, problem.init, [-(10**9), -1, 0])
        return flat_problem
    stages = goal_stages(problem, hierarchy)
    return replace(prepared, stages=stages)
