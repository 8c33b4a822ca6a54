"""Pre-images of goals (conjunctions of atoms) under operator instances.

:func:`preimage` regresses a :class:`~nowplan.core.atoms.Goal` through one
action at its level (seed 002 II-A/B), :func:`regress_through` through a
sequence, and :func:`static_drop` names the static predicates kept out of
pre-images.  The search over fact ids (:mod:`nowplan.planning.subgoals`)
computes the same per node.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from nowplan.belief.protocols import ListsFacts, offers
from nowplan.core.atoms import Atom, Goal, conjoin, contradiction
from nowplan.core.domain import Domain
from nowplan.core.goal_index import regress_step, table_of
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action


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
    pre = [p for p in action.preconditions(level) if p.predicate not in drop]
    if len(table_of(goal)) == len(goal.atoms):
        # the goal's indexes: what the step touches is checked (core/goal_index.py)
        return regress_step(goal, effects, pre, rules)
    # a goal with two atoms of one fluent (made directly from atoms): every atom is read
    remaining: list[Atom] = []
    for a in goal.atoms:
        e = effects.get(a.key)
        if e is None:
            remaining.append(a)
        elif not rules.rule(a.predicate).entails(e.value, a.value):
            return None
    if rules.conflicts and remaining:
        effs = list(effects.values())
        if contradiction(effs + remaining, rules, new=effs) is not None:
            return None
    return conjoin(Goal(frozenset(remaining)), pre, rules)


def static_drop(domain: Domain, belief: Any, lists_facts: bool | None = None) -> frozenset[str]:
    """Static predicates checked at grounding and kept out of pre-images (when the belief lists facts)."""
    if not (offers(belief, ListsFacts) if lists_facts is None else lists_facts):
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

