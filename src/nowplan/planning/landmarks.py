"""Fact landmarks and the landmark-count heuristic, for LAMA-style search.

A *landmark* is a fact every plan makes true at some point (Hoffmann,
Porteous and Sebastia).  Landmarks are found by Zhu and Givan's propagation
over the delete relaxation: a fact's landmark set is the fact itself plus
what every one of its achievers needs,

    LM(f) = {f} ∪ ⋂_{a achieves f} ⋃_{p ∈ pre(a)} LM(p),   LM(f) = {f} for f true now,

computed to a fixpoint; the task's landmarks are the union over the goal
facts.  A landmark l' in LM(l) comes before l (a natural ordering).

The *landmark count* of a state (Richter and Westphal's LAMA, without its
reasonable orderings) counts the landmarks not yet *accepted* on the path
to it (true at some state of the path) plus the accepted ones that are
*required again*: false now and a goal, or needed before a landmark not yet
accepted.  Acceptance is path-dependent, so the search keeps an accepted set
per state.  Preferred operators: applicable actions that make an
unaccepted landmark true.
"""

from __future__ import annotations

from nowplan.planning.task import Task


def landmark_sets(task: Task) -> list[frozenset[int] | None]:
    """``LM(f)`` for each fact id (``None`` where the relaxation never reaches f)."""
    nf = len(task.facts)
    lm: list[frozenset[int] | None] = [None] * nf
    for f in task.init:
        lm[f] = frozenset((f,))
    pre, add, by_pre = task.pre, task.add, task.by_pre
    missing = [len(p) for p in pre]
    ready = [a for a, m in enumerate(missing) if m == 0]
    reached = set(task.init)
    queue = list(task.init)
    # first pass: what the relaxation reaches (an action fires once all its preconditions are reached)
    while queue or ready:
        while ready:
            a = ready.pop()
            for e in add[a]:
                if e not in reached:
                    reached.add(e)
                    queue.append(e)
        if queue:
            f = queue.pop()
            for a in by_pre.get(f, ()):
                missing[a] -= 1
                if missing[a] == 0:
                    ready.append(a)
    # fixpoint: shrink each fact's set by every achiever's union, re-examining dependants on change
    work = [a for a in range(len(pre)) if all(p in reached for p in pre[a])]
    pending = set(work)
    while work:
        a = work.pop()
        pending.discard(a)
        sets = [lm[p] for p in pre[a]]
        if any(s is None for s in sets):
            continue
        union: frozenset[int] = frozenset().union(*sets)  # type: ignore[arg-type]
        for e in add[a]:
            if e in task.init:
                continue
            cand = union | {e}
            old = lm[e]
            new = cand if old is None else old & cand
            if new != old:
                lm[e] = new
                for b in by_pre.get(e, ()):
                    if b not in pending:
                        pending.add(b)
                        work.append(b)
    return lm


class LandmarkCount:
    """``evaluate(state, accepted) -> (h, preferred)``; ``accepted`` is the path's accepted set."""

    def __init__(self, task: Task) -> None:
        self.task = task
        lm = landmark_sets(task)
        found: set[int] = set()
        self.unreachable = False
        for g in task.goal:
            s = lm[g]
            if s is None:
                self.unreachable = True
                continue
            found |= s
        self.landmarks = frozenset(found)
        self.goal = frozenset(task.goal)
        # landmark -> the landmarks it comes before (it is in their LM set)
        before: dict[int, list[int]] = {}
        for l2 in found:
            s = lm[l2]
            for l1 in s or ():
                if l1 != l2 and l1 in found:
                    before.setdefault(l1, []).append(l2)
        self.before = before
        # actions that make each landmark true
        self.achievers: dict[int, list[int]] = {}
        for a, adds in enumerate(task.add):
            for e in adds:
                if e in found:
                    self.achievers.setdefault(e, []).append(a)
        self.evaluations = 0

    def initial_accepted(self) -> frozenset[int]:
        return self.landmarks & self.task.init

    def accept(self, accepted: frozenset[int], state: frozenset[int]) -> frozenset[int]:
        new = self.landmarks & state
        return accepted if new <= accepted else accepted | new

    def evaluate(self, state: frozenset[int], accepted: frozenset[int]) -> tuple[float, list[int]]:
        self.evaluations += 1
        if self.unreachable:
            return float("inf"), []
        todo = self.landmarks - accepted
        again = 0
        for l1 in accepted:
            if l1 in state:
                continue
            if l1 in self.goal or any(l2 in todo for l2 in self.before.get(l1, ())):
                again += 1
        h = len(todo) + again
        if h == 0 and not all(g in state for g in self.goal):
            h = 1  # every landmark met but the goal not: never zero off the goal
        preferred = sorted({
            a for l1 in todo for a in self.achievers.get(l1, ())
            if all(p in state for p in self.task.pre[a])
        })
        return float(h), preferred

