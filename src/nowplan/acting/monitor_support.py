"""What the expected-vs-observed monitor needs from a domain (seed 003).

A domain carries a :class:`MonitorSupport` (``Domain(monitor=...)``): a distance
between world models (states), optionally its own planner (the seed uses
a means-ends planner; without one the monitor uses the regression
planner), an ``adapt`` function that fits a stored or continued action
sequence to the current state (the seed's low-level behaviours, e.g. the
arm starts from wherever it is), and the predicates that describe the
agent's own body and so never enter a restore target.  A domain that
gives none gets :func:`fluent_distance`, the number of fluents whose
values differ.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.atoms import Atom, Goal
from nowplan.belief.protocols import HasState, ListsFacts
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.errors import ModelError
from nowplan.planning.plan import Plan, PlanResult, PlanStep
from nowplan.planning.regression import preimage

Distance = Callable[[State, State], float]
StatePlanner = Callable[[Domain, Mapping[str, str | None], State, Goal, random.Random], PlanResult]
Adapt = Callable[[Sequence[Action], State], list[Action]]


def fluent_distance(a: State, b: State) -> float:
    """How many fluents have different values in ``a`` and ``b`` (absent = False)."""
    return float(a.differing(b))


@dataclass(frozen=True)
class MonitorSupport:
    """What a domain gives the expected-vs-observed monitor (``Domain(monitor=...)``)."""

    distance: Distance = fluent_distance
    planner: StatePlanner | None = field(default=None, compare=False)
    adapt: Adapt | None = field(default=None, compare=False)
    ignore: frozenset[str] = frozenset()  # predicates of the agent's own body


def support_for(domain: Domain) -> MonitorSupport:
    """The domain's own support (``Domain(monitor=...)``), else the fluent-count distance alone."""
    return domain.monitor or MonitorSupport()


def state_of(belief: Any) -> State:
    """The belief's point state (the observed world model)."""
    if isinstance(belief, HasState) and isinstance(belief.state, State):
        return belief.state
    if isinstance(belief, State):
        return belief
    if isinstance(belief, ListsFacts):
        return State(belief.atoms())
    raise ModelError(
        f"the monitor needs a point belief with a State (got {type(belief).__name__}); "
        "use a symbolic belief"
    )


def simulate(domain: Domain, state: State, actions: Sequence[Action],
             closure: Callable[[State], State] | None = None) -> list[State] | None:
    """``[s0, s1, …, sn]`` applying each action's effects (and ``closure``, the derived atoms recomputed:
    :func:`nowplan.planning.derived_state.derived_closure`); ``None`` if a precondition fails."""
    states = [state]
    for act in actions:
        if not all(domain.holds(p, state) for p in act.preconditions(None)):
            return None
        state = state.apply(act.effects())
        if closure is not None:
            state = closure(state)
        states.append(state)
    return states


def drop_loops(states: Sequence[State], actions: Sequence[Action]) -> list[Action]:
    """``actions`` without every stretch that returns to a state it passed through before.

    ``states`` is ``simulate``'s ``[s0, …, sn]`` for ``actions``.  A composed repair (plan
    back to the expected model, then the rest of the old plan) often undoes itself: it puts a
    package down where it was expected and the old plan's next step picks it up again.  From
    the first visit of a state the actions after its last visit apply (the state is the same),
    so cutting the stretch in between keeps the plan valid and reaching the same end.
    """
    last = {s: i for i, s in enumerate(states)}
    out: list[Action] = []
    i = 0
    while i < len(actions):
        j = last[states[i]]
        if j > i:
            i = j
            continue
        out.append(actions[i])
        i += 1
    return out


def plan_from_actions(
    domain: Domain, actions: Sequence[Action], goal: Goal, levels: LevelMap | None = None
) -> Plan | None:
    """A plan with pre-images for an action sequence: regress ``goal`` back through it.

    ``None`` when an action destroys what a later step or the goal needs.
    """
    levels = levels or flat_levels()
    goals = [goal]
    g = goal
    for act in reversed(actions):
        pre = preimage(g, act, levels.level(act), domain)
        if pre is None:
            return None
        goals.append(pre)
        g = pre
    goals.reverse()
    steps = [PlanStep(None, goals[0])]
    steps += [PlanStep(act, gi) for act, gi in zip(actions, goals[1:], strict=True)]
    return Plan(tuple(steps), levels)


def target_goal(atoms: Sequence[Atom] | Goal, ignore: frozenset[str], domain: Domain) -> Goal | None:
    """A goal from a model's atoms, without the agent's own-body predicates."""
    kept = [a for a in atoms if a.predicate not in ignore]
    try:
        return Goal.of(kept, domain.rules)
    except ModelError:
        return None
