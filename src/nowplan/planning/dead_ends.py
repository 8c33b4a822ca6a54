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

from collections.abc import Callable, Iterable, Iterator
from typing import Any
from dataclasses import dataclass

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Problem
from nowplan.core.operators import Action, Operator
from nowplan.core.state import State
from nowplan.planning.task_grounding import adders_of, grounding


@dataclass(frozen=True)
class Irreversible:
    action: Action
    atom: Atom  # deleted by ``action`` and never reachable again

    def __str__(self) -> str:
        return f"{self.action.pddl()} deletes {self.atom}, which no action sequence makes true again"


def _restorable(missing: set[Atom], adders: Callable[[Atom], Iterable[frozenset[Atom]]]) -> set[Atom]:
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
            if any(not (pre & still) for pre in adders(d)):
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

    # the steps to check, with what they delete (and do not add); only their deleted atoms are looked up
    # below.  Actions of one operator that agree on the arguments of its deletes (and on which deletes an
    # add cancels) delete the same atoms: the first of them stands for the rest (``same``), whose effects
    # are not even bound here unless a lost atom makes their own adds matter (every fly of zenotravel-25
    # from one city at one fuel level: 5800 actions, 350 delete sets)
    steps: list[tuple[Action, frozenset[Atom]]] = []
    same: dict[Any, list[Action]] = {}
    shape: dict[str, Any] = {}
    seen = 0
    for act in g.actions:
        if seen >= limit:
            break
        if not below_top(act):
            continue
        op = act.operator
        sh = shape.get(op.name)
        if sh is None:
            sh = shape[op.name] = _delete_shape(op)
        if sh is None:
            continue  # deletes nothing
        seen += 1
        key = (op.name, *_key_of(act, shape))
        group = same.get(key)
        if group is not None:
            group.append(act)
            continue
        effs = act.effects()
        dels = frozenset(neg(e) for e in effs if e.value is False).difference(
            [e for e in effs if e.value is True])
        same[key] = [act]
        if dels:
            steps.append((act, dels))
    # the adders of a deleted atom, from the grounding's index (made once, kept for later readers: the
    # executive's direct refinements), each with its positive preconditions made on the first ask only:
    # restoring an atom needs one adder whose preconditions avoid what is still missing, mostly the first
    index = adders_of(g)
    pre_of: dict[int, frozenset[Atom]] = {}

    def adders(d: Atom) -> Iterator[frozenset[Atom]]:
        for a in index.get(d, ()):
            pre = pre_of.get(id(a))
            if pre is None:
                pre = pre_of[id(a)] = frozenset(p for p in a.preconditions() if p.value is True)
            yield pre

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
    firsts: list[tuple[Action, frozenset[Atom], set[Atom]]] = []
    for act, dels in steps:
        back = restorable.get(dels)
        if back is None:
            back = restorable[dels] = _restorable(set(dels), adders)
        if len(back) < len(dels):
            firsts.append((act, dels, back))
    if not firsts:
        return None  # every deleted atom can be made true again
    # some atoms cannot be restored: whether losing one is harmless depends on each action's own adds,
    # so every action of those groups is checked, in grounding order (the first irreversible one is reported)
    order = {id(a): k for k, a in enumerate(g.actions)}
    todo = sorted(((a, dels, back) for first, dels, back in firsts
                   for a in same[(first.operator.name, *_key_of(first, shape))]), key=lambda x: order[id(x[0])])
    for act, dels, back in todo:
        adds = {e for e in act.effects() if e.value is True}
        lost = sorted((d for d in dels - back if not harmless(d, act, adds)), key=str)
        if lost:
            return Irreversible(act, lost[0])
    return None


def _delete_shape(op: Operator) -> tuple[tuple[int, ...], list[list[tuple[Any, Any]]]] | None:
    """What an instance's delete set depends on: the parameter positions in ``op``'s deletes, and per
    (delete, add) pair of one predicate and arity, the argument terms that must agree for the add to
    cancel the delete (a position, or a constant as a 1-tuple).  None: ``op`` deletes nothing."""
    index = {v: i for i, v in enumerate(op.params)}

    def term(t: Any) -> Any:
        return index[t] if isinstance(t, Var) else (t,)

    dels = [e for e in op.effects if e.value is False]
    if not dels:
        return None
    if any(isinstance(t, Var) and t not in index for e in op.effects for t in e.args):
        return tuple(range(len(op.params))), []  # (a variable that is no parameter: one group per instance)
    positions = tuple(sorted({index[t] for e in dels for t in e.args if isinstance(t, Var)}))
    pairs = [[(term(x), term(y)) for x, y in zip(d.args, a.args, strict=True)]
             for d in dels for a in op.effects
             if a.value is True and a.predicate == d.predicate and len(a.args) == len(d.args)]
    return positions, pairs


def _key_of(act: Action, shape: dict[str, Any]) -> tuple[Any, Any]:
    positions, pairs = shape[act.operator.name]
    args = act.args
    return (tuple(args[i] for i in positions),
            tuple(all((args[x] if isinstance(x, int) else x[0]) == (args[y] if isinstance(y, int) else y[0])
                      for x, y in pair) for pair in pairs))
