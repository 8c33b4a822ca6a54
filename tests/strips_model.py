"""An independent model of the STRIPS semantics the planner's plans must respect.

Written from the definitions, not with nowplan's grounder, planner or pre-image function:
closed-world truth, the net effect of an action (effects apply in order, the last one on a
fluent wins, as in ``State.apply`` and the PDDL reader's deletes-then-adds), and the
regression of a goal through an action at a level (the plan contract of
``nowplan.planning.regression.plan``).  Used by tests/test_planner_property.py and
tests/test_pddl_property.py.
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping, Sequence
from typing import Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.core.state import State

Key = tuple[str, tuple[Any, ...]]


def _bind(a: Atom, b: Mapping[Var, Any]) -> Atom:
    return Atom(a.predicate, tuple(b.get(t, t) if isinstance(t, Var) else t for t in a.args), a.value)


def _bindings(act: Action) -> dict[Var, Any]:
    return dict(zip(act.operator.params, act.args, strict=True))


def statics(domain: Domain) -> frozenset[str]:
    """Predicates no operator changes (their preconditions are checked when grounding)."""
    changed = {e.predicate for op in domain.operators for e in op.effects}
    return frozenset(p for p in domain.predicates if p not in changed)


def pre_of(act: Action, level: int | None) -> list[Atom]:
    """Ground preconditions of criticality > level (all when level is None)."""
    b = _bindings(act)
    return [
        _bind(p.atom, b)
        for p in act.operator.preconditions
        if level is None or p.criticality > level
    ]


def net_effects(act: Action) -> dict[Key, Any]:
    """Each fluent's value after the action: effects apply in order, the last one wins."""
    out: dict[Key, Any] = {}
    for e in act.operator.effects:
        g = _bind(e, _bindings(act))
        out[g.key] = g.value
    return out


def truth(state: State, a: Atom) -> bool:
    """Closed world: an absent fluent is false."""
    return (state.value(a.key) is not False) == bool(a.value)


def applicable(act: Action, state: State) -> bool:
    return all(truth(state, p) for p in pre_of(act, None))


def step(state: State, act: Action) -> State:
    m: dict[Key, Any] = {a.key: a.value for a in state.atoms()}
    for k, v in net_effects(act).items():
        if v is False:
            m.pop(k, None)
        else:
            m[k] = v
    return State(m)


def ground_actions(domain: Domain, objects: Sequence[str], init: State) -> list[Action]:
    """All instances whose static preconditions hold (the same for every state)."""
    stat = statics(domain)
    out = []
    for op in domain.operators:
        for vals in itertools.product(objects, repeat=len(op.params)):
            act = op.instantiate(dict(zip(op.params, vals, strict=True)))
            if all(truth(init, p) for p in pre_of(act, None) if p.predicate in stat):
                out.append(act)
    return out


def level_of(levels: LevelMap, act: Action) -> int:
    """The action's level in the map: its override, else the map's top."""
    return dict(levels.overrides).get(act.key, levels.top)


def regress(goal: frozenset[Atom], act: Action, level: int, stat: frozenset[str]) -> frozenset[Atom] | None:
    """``g(i-1)`` from ``g(i)`` and ω at ``level``, written from the definition of a pre-image.

    Goal atoms the action makes true are dropped; one it makes false (sets to another value)
    fails the regression; the preconditions of criticality above ``level`` are added, except
    those of static predicates (checked when grounding, and left out of pre-images when the
    belief lists its facts, as a State does); one value per fluent, a clash fails.
    """
    eff = net_effects(act)
    table: dict[Key, Any] = {}
    for a in goal:
        if a.key in eff:
            if eff[a.key] != a.value:
                return None
            continue
        table[a.key] = a.value
    for p in pre_of(act, level):
        if p.predicate in stat:
            continue
        if p.key in table and table[p.key] != p.value:
            return None
        table[p.key] = p.value
    return frozenset(Atom(k[0], k[1], v) for k, v in table.items())
