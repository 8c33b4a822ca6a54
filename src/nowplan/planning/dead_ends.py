"""Irreversible concrete steps: where an abstraction hierarchy may lead the executive into a dead end.

HPN executes the first steps of an abstract plan before the rest is refined.
If a concrete step can destroy something that can never be restored (fuel
in nomystery: a truck's fuel only goes down), an abstract plan that ignores
it may spend it, and no plan exists from there.  :func:`irreversible_step`
finds such a step among the actions whose effects are below the top level.

The test is sound and incomplete: for a ground action ``a`` reachable in the
delete relaxation, each atom ``d`` it deletes (and does not add back) is
checked for relaxed reachability from *every* relaxed-reachable atom except
``a``'s deletes (a lost atom that is not a goal and whose every consumer
gives only what ``a`` gave for good is harmless: a key taken for ever).
Relaxed reachability is monotone in its start, and every
real state after ``a`` is a subset of that start, so if ``d`` is unreachable
from it, ``d`` never holds again after ``a``.  Since every other reachable
atom is in that start, only the deleted atoms can be restored, which takes
one pass over their achievers per round.  It checks at most ``limit``
actions (in grounding order) and stops at the first irreversible one.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any
from dataclasses import dataclass

from nowplan.core.atoms import Atom
from nowplan.core.domain import Problem
from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.planning.task_grounding import adders_of, grounding


@dataclass(frozen=True)
class Irreversible:
    action: Action
    atom: Atom  # deleted by ``action`` and never reachable again

    def __str__(self) -> str:
        return f"{self.action.pddl()} deletes {self.atom}, which no action sequence makes true again"


def _restorable(missing: set[Atom], adders: dict[Atom, list[frozenset[Atom]]]) -> set[Atom]:
    """Which of ``missing`` become reachable again from ``reached - missing`` (delete relaxation).

    Every other relaxed-reachable atom is in the start, so only the missing
    atoms can be added: one is restored when some adder's preconditions avoid
    every atom still missing.  At most ``len(missing)`` rounds.
    """
    still = set(missing)
    grew = True
    while grew and still:  # (the fixpoint does not depend on the order the atoms are tried in)
        grew = False
        for d in list(still):
            if any(not (pre & still) for pre in adders.get(d, ())):
                still.discard(d)
                grew = True
    return missing - still


def irreversible_step(problem: Problem, below_top: Callable[[Action], bool],
                      limit: int = 100_000) -> Irreversible | None:
    """The first concrete step (``below_top(action)``) whose delete can never be undone, or None."""
    if not isinstance(problem.init, State):
        return None
    g = grounding(problem.domain, problem.objects, problem.init, -1)
    # the negation of each deleted atom, made once (many actions delete the same atom: every flight
    # from a city), so the sets below hold the same objects and compare them by identity
    negated: dict[Atom, Atom] = {}

    def neg(e: Atom) -> Atom:
        n = negated.get(e)
        if n is None:
            n = negated[e] = e.negate()
        return n

    # the steps to check, with what they delete (and do not add); only their deleted atoms are looked up below
    steps: list[tuple[Action, frozenset[Atom]]] = []
    for act in g.actions:
        if len(steps) >= limit:
            break
        if not below_top(act):
            continue
        effs = act.effects()
        gone = [neg(e) for e in effs if e.value is False]
        if not gone:
            continue
        dels = frozenset(gone).difference([e for e in effs if e.value is True])
        if dels:
            steps.append((act, dels))
    wanted = set().union(*(d for _, d in steps))
    # the adders of the deleted atoms, from the grounding's index (made once, kept for later readers:
    # the executive's direct refinements), in grounding order as before
    index = adders_of(g)
    pre_of: dict[Any, frozenset[Atom]] = {}
    adders: dict[Atom, list[frozenset[Atom]]] = {}
    for d in wanted:
        for a in index.get(d, ()):
            pre = pre_of.get(a.key)
            if pre is None:
                pre = pre_of[a.key] = frozenset(p for p in a.preconditions() if p.value is True)
            adders.setdefault(d, []).append(pre)
    goal = {a for a in problem.goal.atoms if a.value is True}
    lazy: dict[str, Any] = {}  # what only a lost atom needs: every deleted atom, the consumers

    def harmless(lost: Atom, act: Action, adds: set[Atom]) -> bool:
        # nothing needs it any more: not a goal, and everything its consumers give is already
        # given by ``act`` and never taken away (a key taken in lights: ``has`` stays true)
        if lost in goal:
            return False
        if not lazy:
            lazy["deleted"] = {neg(e) for a in g.actions for e in a.effects() if e.value is False}
            consumers: dict[Atom, list[Action]] = {}
            for a in g.actions:
                for p in a.preconditions():
                    if p.value is True:
                        consumers.setdefault(p, []).append(a)
            lazy["consumers"] = consumers
        deleted: set[Atom] = lazy["deleted"]
        return all(e.value is not True or (e in adds and e not in deleted)
                   for c in lazy["consumers"].get(lost, ()) for e in c.effects())

    restorable: dict[frozenset[Atom], set[Atom]] = {}  # many actions delete the same atoms (one per target)
    for act, dels in steps:
        back = restorable.get(dels)
        if back is None:
            back = restorable[dels] = _restorable(set(dels), adders)
        if len(back) == len(dels):
            continue  # every deleted atom can be made true again
        adds = {e for e in act.effects() if e.value is True}
        lost = sorted((d for d in dels - back if not harmless(d, act, adds)), key=str)
        if lost:
            return Irreversible(act, lost[0])
    return None
