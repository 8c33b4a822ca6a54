"""Fact landmarks and the landmark-count heuristic, for LAMA-style search.

A *landmark* is a fact every plan makes true at some point (Hoffmann,
Porteous and Sebastia).  Landmarks are found by Zhu and Givan's propagation
over the delete relaxation: a fact's landmark set is the fact itself plus
what every one of its achievers needs,

    LM(f) = {f} ∪ ⋂_{a achieves f} ⋃_{p ∈ pre(a)} LM(p),   LM(f) = {f} for f true now,

computed to a fixpoint; the task's landmarks are the union over the goal
facts.

The *landmark count* of a state (Richter and Westphal's LAMA, without its
reasonable orderings) counts the landmarks not yet *accepted* on the path
to it (true at some state of the path) plus the accepted ones that are
*required again*: false now and a goal, or necessarily ordered before a
landmark not yet accepted (needed by every first achiever of it).
Acceptance is path-dependent, so the search keeps an accepted set per
state.  Preferred operators: applicable actions that make an unaccepted
landmark true.

Disjunctive landmarks (one step back from the fact landmarks, sharing no
fact, as in Fast Downward's landmark graph) and reasonable orderings come
from :mod:`nowplan.planning.lm_orders` (``orders=False`` leaves them out): a
landmark reached while a reasonable predecessor is not yet accepted still
counts.  Measured with benchmarks/classical.py --time-limit 10 in one
period (benchmarks/results/classical_orders against the main branch's run):
plans within 10 % of lama-first's cost on 64 of 65 instances against 62
(gripper p03-p05 now carry two balls per trip; barman p02 got worse, 51
against 45), wall-time ratio to lama-first 1.08x against 1.00x (geometric
mean).  An earlier try with overlapping disjunctive landmarks and no
reasonable orderings was worse (floortile p04 16,410 expansions against
10,088 without; 3,984 now).  The first achievers of the disjunctive
landmarks come from one labelled propagation for all of them
(:func:`nowplan.planning.lm_orders.prime_first_achievers`), not one relaxed
exploration each: on a 2,560-action logistics task the graph takes ~40 ms
instead of ~150 ms (benchmarks/results/classical_lmspeed).

The executive builds a graph per planner call (a few hundred per HPN run),
mostly for goals that hold but for an atom or two, so the per-call build
reads only what the graph needs: the landmark sets of the goal's cone
(:func:`landmark_sets` with ``goal``), first achievers from the adders index
(kept with the task structure across calls, :func:`nowplan.planning.lm_orders.fact_adders`)
and, given lama's compiled kernel, the relaxed exploration, the fixpoint and the
labelled propagation in C.  The graph is the same (tests/test_lm_same_graph.py
against a frozen copy of the earlier construction); on auto-HPN over logistics
with 40 packages (201 calls) the construction fell from 12.1 s to 1.2 s under
cProfile, planning CPU from 2.9 s to 1.2 s (benchmarks/results/lm_per_call).
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable
from typing import TYPE_CHECKING

from nowplan.planning.axioms import relaxed_task
from nowplan.planning.lm_orders import (
    Mutex,
    fact_adders,
    disjunctive_landmarks,
    first_achievers as possible_first,
    prime_first_achievers,
    reasonable_orders,
    relaxed_order,
    relaxed_reached,
    set_relaxed_order,
)
from nowplan.planning.task import Task

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel


def landmark_sets(task: Task, goal: Iterable[int] | None = None, native: Kernel | None = None
                  ) -> list[frozenset[int] | None]:
    """``LM(f)`` for each fact id (``None`` where the relaxation never reaches f).

    With ``goal``, only the facts of the goal's *cone* get their set (the rest
    stay ``None``): the goal facts not true now, the preconditions not true now
    of every action adding a cone fact, and so on.  ``LM(f)`` of a cone fact
    depends only on the cone's actions (its achievers, their preconditions'
    sets, and ``{p}`` for a precondition true now), so the cone's sets are the
    whole task's.  An HPN call whose goal holds but for a few atoms explores a
    small part of the task.  With ``native`` (the compiled kernel of ``task``'s
    actions) the fixpoint runs in C, with the same sets.
    """
    order = relaxed_order(task)  # breadth first: the order in which actions become applicable
    cone: set[int] | None = None
    if goal is not None:
        cone = _cone(task, goal)
        order = [a for a in order if a in cone]
    if native is not None:
        return native.landmark_sets(task.init, order)
    nf = len(task.facts)
    lm: list[frozenset[int] | None] = [None] * nf
    init = task.init
    for f in init:
        lm[f] = frozenset((f,))
    pre, add, by_pre = task.pre, task.add, task.by_pre
    # fixpoint: shrink each fact's set by every achiever's union, re-examining dependants on change;
    # in that order most sets are final the first time (the fixpoint does not depend on the order)
    work = deque(order)
    pending = set(order)
    while work:
        a = work.popleft()
        pending.discard(a)
        sets = [lm[p] for p in pre[a]]
        if any(s is None for s in sets):
            continue
        union: frozenset[int] = frozenset().union(*sets)  # type: ignore[arg-type]
        for e in add[a]:
            if e in init:
                continue
            cand = union | {e}
            old = lm[e]
            new = cand if old is None else old & cand
            if new != old:
                lm[e] = new
                for b in by_pre.get(e, ()):
                    if b not in pending and (cone is None or b in cone):
                        pending.add(b)
                        work.append(b)
    return lm


def _cone(task: Task, goal: Iterable[int]) -> set[int]:
    """The actions adding a fact of the goal's cone (see :func:`landmark_sets`)."""
    adders, pre, init = fact_adders(task), task.pre, task.init
    stack = [g for g in set(goal) if g not in init]
    facts = set(stack)
    acts: set[int] = set()
    while stack:
        f = stack.pop()
        for a in adders.get(f, ()):
            if a in acts:
                continue
            acts.add(a)
            for p in pre[a]:
                if p not in init and p not in facts:
                    facts.add(p)
                    stack.append(p)
    return acts


def first_achievers(task: Task, facts: frozenset[int]) -> dict[int, list[int]]:
    """Fact -> the actions that may first make it true: they add it, do not need it, are relaxed-reachable."""
    pre, adders, reached = task.pre, fact_adders(task), relaxed_reached(task)
    out: dict[int, list[int]] = {}
    for e in sorted(facts):
        acts = [a for a in adders.get(e, ()) if e not in pre[a] and all(p in reached for p in pre[a])]
        if acts:
            out[e] = acts
    return out


class LandmarkCount:
    """``evaluate(state, accepted) -> (h, preferred)``; ``accepted`` is the path's accepted set.

    Landmarks are numbered sets of facts (``sets``; the kernel also takes
    disjunctions, here each is one fact landmark, in fact order).  A landmark
    is accepted (its index in the accepted set) once one of its facts holds.
    """

    def __init__(self, task: Task, orders: bool = True, native: Kernel | None = None) -> None:
        nactions = len(task.pre)
        mutex = task.memo.get("mutex")
        task = relaxed_task(task)  # derived facts are reached by the rules (relaxed actions of cost 0)
        self.native = native
        if native is not None:  # the kernel of this relaxed task (h_FF's): the relaxed exploration in C
            set_relaxed_order(task, native)
        self.task = task
        lm = landmark_sets(task, task.goal, native)  # the goal's cone: what the graph reads
        found: set[int] = set()
        self.unreachable = False
        for g in task.goal:
            s = lm[g]
            if s is None:
                self.unreachable = True
                continue
            found |= s
        self.landmarks = frozenset(found)  # the fact landmarks
        self.goal = frozenset(task.goal)
        self.sets: list[frozenset[int]] = [frozenset((f,)) for f in sorted(found)]
        self.before = self._orderings(task, lm)
        self.reasonable: dict[int, list[int]] = {}
        if orders and not self.unreachable:
            self._add_orders(task, mutex, lm)
        self.is_goal = [len(d) == 1 and next(iter(d)) in self.goal for d in self.sets]
        self.of_fact: dict[int, list[int]] = {}
        for i, d in enumerate(self.sets):
            for f in sorted(d):
                self.of_fact.setdefault(f, []).append(i)
        # actions that make each landmark true
        self.achievers: dict[int, list[int]] = {}
        adders = fact_adders(task)
        for i, d in enumerate(self.sets):
            acts = sorted({a for f in d for a in adders.get(f, ()) if a < nactions})
            if acts:
                self.achievers[i] = acts
        self.evaluations = 0

    def _orderings(self, task: Task, lm: list[frozenset[int] | None]) -> dict[int, list[int]]:
        """Necessary orderings: landmark -> the landmarks it must hold right before.

        A fact landmark l1 comes necessarily before a fact landmark l2 not
        true now if every first achiever of l2 needs l1.  Only these orderings
        make an accepted landmark *required again*; a natural ordering alone
        does not (a package's first place comes before its goal place, but
        need not hold again once the package is picked up: counting it again
        made picking a package up look like a step back).
        """
        pre, init = task.pre, task.init
        index = {next(iter(d)): i for i, d in enumerate(self.sets)}
        achievers = first_achievers(task, self.landmarks)
        before: dict[int, list[int]] = {}
        for l2 in sorted(self.landmarks):
            acts = achievers.get(l2)
            if not acts or l2 in init:
                continue
            common = set(pre[acts[0]]).intersection(*(pre[a] for a in acts[1:]))
            for l1 in sorted(common & self.landmarks):
                before.setdefault(index[l1], []).append(index[l2])
        return before

    def _add_orders(self, task: Task, mutex: Mutex | None, lm_sets: list[frozenset[int] | None]) -> None:
        """Disjunctive landmarks and reasonable orderings (:mod:`nowplan.planning.lm_orders`)."""
        index = {next(iter(d)): i for i, d in enumerate(self.sets)}
        of_set: dict[frozenset[int], int] = {}
        found = disjunctive_landmarks(task, self.landmarks, lm_sets)
        # the sets whose first achievers need an exploration: one propagation for them all
        prime_first_achievers(task, [d for d, _ in found] + [frozenset((f,)) for f in self.landmarks
                                                             if f in task.init], lm_sets, self.native)
        for d, lm in found:
            if d in of_set:
                self.before.setdefault(of_set[d], []).append(index[lm])
                continue
            i = of_set[d] = len(self.sets)
            self.sets.append(d)
            self.before.setdefault(i, []).append(index[lm])
            acts = possible_first(task, d)
            if acts:
                common = set(task.pre[acts[0]]).intersection(*(task.pre[a] for a in acts[1:]))
                for f in sorted(common & self.landmarks):
                    self.before.setdefault(index[f], []).append(i)
        self.reasonable = reasonable_orders(task, self.sets, self.before, self.goal, mutex, lm_sets)

    def initial_accepted(self) -> frozenset[int]:
        return self.accept(frozenset(), self.task.init)

    def accept(self, accepted: frozenset[int], state: frozenset[int]) -> frozenset[int]:
        of_fact = self.of_fact
        new = {i for f in state for i in of_fact.get(f, ())}
        return accepted if new <= accepted else accepted | new

    def evaluate(self, state: frozenset[int], accepted: frozenset[int]) -> tuple[float, list[int]]:
        self.evaluations += 1
        if self.unreachable:
            return float("inf"), []
        n = len(self.sets)
        todo = [i for i in range(n) if i not in accepted]
        todoset = set(todo)
        again = 0
        for i in accepted:
            if any(j not in accepted for j in self.reasonable.get(i, ())):
                again += 1  # reached before a reasonable predecessor: to be reached again
                continue
            if self.sets[i] & state:
                continue
            if self.is_goal[i] or any(j in todoset for j in self.before.get(i, ())):
                again += 1
        h = len(todo) + again
        if h == 0 and not all(g in state for g in self.goal):
            h = 1  # every landmark met but the goal not: never zero off the goal
        preferred = sorted({
            a for i in todo for a in self.achievers.get(i, ())
            if all(p in state for p in self.task.pre[a])
        })
        return float(h), preferred
