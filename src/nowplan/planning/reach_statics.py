"""Reachability statics: keep abstract levels from choosing actions no concrete plan can apply.

An abstract level drops preconditions, so an abstract plan may use an action
whose dropped precondition can never hold: in IPC logistics the top level
may load a package into a truck parked in another city, because
``load-truck`` does not say the truck must be able to reach the place.  No
hierarchy derived from the domain alone can exclude that (Knoblock's
hierarchies are ordered monotonic, not downward refinable); the problem can.

:func:`add_reachability_statics` computes the atoms reachable from the
initial state in the delete relaxation of the *concrete* problem (every
precondition kept) and, for each droppable positive precondition
``p(args)`` (criticality below the top), adds the static precondition
``reachable-p(args)`` (kept at every level), with the reachable ``p`` atoms
as its facts in the initial state.  Where every ``p`` atom is reachable the
static prunes nothing and costs the grounder one more join.  Relaxed
reachability over-approximates the reachable states, so an action instance
excluded this way is applicable in no reachable state: no concrete plan
changes, and abstract plans lose only steps that could never be refined.
(What nowplan's ``logistics/domain.pddl`` does by hand with ``serves``.)
"""

from __future__ import annotations

import logging
from dataclasses import replace

from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.planning.task_grounding import grounding, share_concrete

log = logging.getLogger(__name__)

PREFIX = "reachable-"


def _name(domain: Domain, pred: str) -> str:
    name = PREFIX + pred
    k = 1
    while name in domain.predicates:  # bounded by the number of predicates
        k += 1
        name = f"{PREFIX}{k}-{pred}"
    return name


def add_reachability_statics(problem: Problem) -> Problem:
    """``problem`` with ``reachable-p`` statics on droppable preconditions (see the module doc).

    Returns ``problem`` unchanged when the domain is flat, when no precondition
    can be dropped, or when the initial state is not a plain :class:`State`.
    """
    domain = problem.domain
    top = domain.max_criticality
    if domain.top_level <= 0 or not isinstance(problem.init, State):
        return problem
    concrete = grounding(domain, problem.objects, problem.init, -1)
    reached = concrete.reached
    by_pred: dict[str, set[Atom]] = {}
    for a in reached:
        by_pred.setdefault(a.predicate, set()).add(a)
    for a in problem.init.atoms():
        if a.value is True:
            by_pred.setdefault(a.predicate, set()).add(a)
    static = domain.static_predicates
    new_preds: dict[str, Predicate] = {}
    new_facts: list[Atom] = []
    ops: list[Operator] = []
    exact = True
    for op in domain.operators:
        extra: list[Precondition] = []
        for p in op.preconditions:
            a = p.atom
            if p.criticality >= top or a.value is not True or a.predicate in static:
                continue  # kept at every level, or not joined by the grounder (a negative condition)
            pred = domain.predicates[a.predicate]
            if not pred.boolean or not a.args:
                exact = False  # dropped without a static: an abstract level may ground more
                continue
            name = new_preds[a.predicate].name if a.predicate in new_preds else _name(domain, a.predicate)
            if a.predicate not in new_preds:
                new_preds[a.predicate] = Predicate(name, pred.arity, pred.arg_types)
                new_facts += [Atom(name, x.args) for x in sorted(by_pred.get(a.predicate, set()), key=repr)]
            extra.append(Precondition(Atom(name, a.args), top))
        ops.append(replace(op, preconditions=(*op.preconditions, *extra)) if extra else op)
    if not new_preds:
        return problem
    log.info("reachability statics added for %s", ", ".join(sorted(new_preds)))
    dom = replace(domain, predicates={**dict(domain.predicates), **{p.name: p for p in new_preds.values()}},
                  operators=tuple(ops))
    init = State([*problem.init.atoms(), *new_facts])
    if exact:  # every level grounds what the concrete level grounded: share it
        share_concrete(concrete, dom, problem.objects, init, [-(10**9), *range(-1, dom.top_level + 1)])
    return replace(problem, domain=dom, init=init)

