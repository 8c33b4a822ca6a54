"""A frozen copy of the landmark graph's construction as it was before the per-call speed-ups
(nowplan.planning.landmarks and lm_orders at main d5f7338), the reference that
tests/test_lm_same_graph.py compares the current code with.  Not to be edited.
"""
# mypy: ignore-errors
# ruff: noqa

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence

from nowplan.planning.axioms import relaxed_task
from nowplan.planning.fact_mutex import FactMutex
from nowplan.planning.task import Task

MAX_DISJUNCTION = 4  # facts of one disjunctive landmark

Mutex = Callable[[int, int], bool]


LMSets = Sequence["frozenset[int] | None"]


def first_achievers_of_set(task: Task, facts: frozenset[int], lm: LMSets | None = None) -> list[int]:
    """Actions adding a fact of ``facts`` that are applicable in the relaxation before any fact of it holds.

    With the fact landmarks of every fact (``lm``, Zhu and Givan's sets) a
    single fact ``L`` needs no exploration: a precondition ``p`` is reachable
    without ``L`` exactly when ``L`` is not in ``LM(p)``.
    """
    pre, add, by_pre = task.pre, task.add, task.by_pre
    if lm is not None and len(facts) == 1:
        (f,) = facts
        if f not in task.init:
            return [a for a in _adders(task).get(f, ())
                    if all(lm[p] is not None and f not in lm[p] for p in pre[a])]  # type: ignore[operator]
    memo = task.memo.setdefault("first_achievers", {})
    hit = memo.get(facts)
    if hit is not None:
        return list(hit)
    adders = _adders(task)
    banned_ids = sorted({a for f in facts for a in adders.get(f, ())})
    banned = [False] * len(pre)
    for a in banned_ids:
        banned[a] = True
    missing = [len(p) for p in pre]
    reached = set(task.init) - facts
    queue = sorted(reached)
    for a, m in enumerate(missing):
        if m == 0 and not banned[a]:
            queue.extend(e for e in add[a] if e not in reached)
    fired = [False] * len(pre)
    done: set[int] = set()
    while queue:
        f = queue.pop()
        if f in facts or f in done:
            continue
        done.add(f)
        reached.add(f)
        for a in by_pre.get(f, ()):
            missing[a] -= 1
            if missing[a] == 0 and not banned[a] and not fired[a]:
                fired[a] = True
                queue.extend(e for e in add[a] if e not in reached and e not in facts)
    out = [a for a in banned_ids if all(p in reached for p in pre[a])]
    memo[facts] = tuple(out)
    return out


def prime_first_achievers(task: Task, families: Sequence[frozenset[int]], lm: LMSets) -> None:
    """Find the first achievers of every fact set in ``families`` at once and memoise them for
    :func:`first_achievers` (same results as its exploration, one per set).

    One propagation in the style of Zhu and Givan's, with a label (a bit) per
    set ``F_k`` instead of a fact: ``need(p)`` holds bit ``k`` exactly when
    ``p`` is unreachable in the delete relaxation once every action adding a
    fact of ``F_k`` is left out (and ``F_k`` is not true initially).  With
    ``pre(a)`` and ``add(a)``,

        need(p) = labels(p) for p true now,
        need(p) = ⋂_{a adds p} (labels(add(a)) ∪ ⋃_{q ∈ pre(a)} need(q)) otherwise,

    where ``labels(X)`` are the sets sharing a fact with ``X``: the greatest
    fixpoint, computed from "unreached" (``None``) downwards as
    :func:`nowplan.planning.landmarks.landmark_sets` does.  The first
    achievers of ``F_k`` are its adders whose preconditions are reachable
    and carry no bit ``k``.  ``lm`` (the fact landmark sets) says which facts
    the relaxation reaches at all.
    """
    memo = task.memo.setdefault("first_achievers", {})
    todo = sorted({f for f in families if f not in memo}, key=sorted)
    if not todo:
        return
    pre, add, by_pre, init = task.pre, task.add, task.by_pre, task.init
    bit_of: dict[int, int] = {}
    for k, fam in enumerate(todo):
        for f in fam:
            bit_of[f] = bit_of.get(f, 0) | 1 << k
    need: list[int | None] = [None] * len(task.facts)
    for f in init:
        need[f] = bit_of.get(f, 0)
    amask = [0] * len(pre)
    for f, bits in bit_of.items():
        for a in _adders(task).get(f, ()):
            amask[a] |= bits
    reachable = [all(lm[p] is not None for p in ps) for ps in pre]
    work = deque(a for a in relaxed_order(task) if reachable[a])
    pending = set(work)
    while work:
        a = work.popleft()
        pending.discard(a)
        u = amask[a]
        unreached = False
        for p in pre[a]:
            n = need[p]
            if n is None:  # not yet reached in this order: a comes again when it is
                unreached = True
                break
            u |= n
        if unreached:
            continue
        for e in add[a]:
            if e in init:
                continue
            old = need[e]
            new = u if old is None else old & u
            if new != old:
                need[e] = new
                for b in by_pre.get(e, ()):
                    if b not in pending and reachable[b]:
                        pending.add(b)
                        work.append(b)
    adders = _adders(task)
    for k, fam in enumerate(todo):
        bit = 1 << k
        acts = sorted({a for f in fam for a in adders.get(f, ())})
        memo[fam] = tuple(a for a in acts if reachable[a] and not any(need[p] & bit for p in pre[a]))  # type: ignore[operator]


def relaxed_order(task: Task) -> list[int]:
    """The actions the delete relaxation applies, in breadth-first order (made once per task)."""
    hit = task.memo.get("relaxed_order")
    if hit is None:
        pre, add, by_pre = task.pre, task.add, task.by_pre
        missing = [len(p) for p in pre]
        order = [a for a, m in enumerate(missing) if m == 0]
        reached = set(task.init)
        frontier = sorted(task.init)
        i = 0
        while frontier or i < len(order):
            while i < len(order):
                for e in add[order[i]]:
                    if e not in reached:
                        reached.add(e)
                        frontier.append(e)
                i += 1
            nxt, frontier = frontier, []
            for f in nxt:
                for a in by_pre.get(f, ()):
                    missing[a] -= 1
                    if missing[a] == 0:
                        order.append(a)
        hit = task.memo["relaxed_order"] = order
    assert isinstance(hit, list)
    return hit


def _adders(task: Task) -> dict[int, list[int]]:
    """Fact -> the actions that add it, ascending (made once per task)."""
    hit = task.memo.get("adders")
    if hit is None:
        hit = {}
        for a, adds in enumerate(task.add):
            for e in adds:
                hit.setdefault(e, []).append(a)
        task.memo["adders"] = hit
    assert isinstance(hit, dict)
    return hit


def disjunctive_landmarks(task: Task, landmarks: Iterable[int], lm: LMSets | None = None
                          ) -> list[tuple[frozenset[int], int]]:
    """``(D, L)``: the disjunctive landmarks ``D`` found one step before each fact landmark ``L``.

    One ``D`` may come with several ``L``; two different ``D`` share no fact.
    """
    facts, init = task.facts, task.init
    known = frozenset(landmarks)
    out: list[tuple[frozenset[int], int]] = []
    found: list[tuple[frozenset[int], int]] = []
    for fact in sorted(known):
        if fact in init:
            continue
        acts = first_achievers_of_set(task, frozenset((fact,)), lm)
        if not acts:
            continue
        by_pred: list[dict[str, set[int]]] = []
        for a in acts:
            groups: dict[str, set[int]] = {}
            for p in task.pre[a]:
                if facts[p].value is True:
                    groups.setdefault(facts[p].predicate, set()).add(p)
            by_pred.append(groups)
        common = set(by_pred[0]).intersection(*by_pred[1:])
        for pred in sorted(common):
            d = frozenset().union(*(g[pred] for g in by_pred))
            if 2 <= len(d) <= MAX_DISJUNCTION and not d & init and not d & known:
                found.append((d, fact))
    # as in FD's landmark graph a fact is in at most one disjunctive landmark: the smaller ones first
    used: set[int] = set()
    chosen: set[frozenset[int]] = set()
    for d, fact in sorted(found, key=lambda x: (len(x[0]), sorted(x[0]), x[1])):
        if d in chosen or not d & used:  # the same set may come before several fact landmarks
            used |= d
            chosen.add(d)
            out.append((d, fact))
    return out


def reasonable_orders(task: Task, sets: Sequence[frozenset[int]], before: Mapping[int, list[int]],
                      goal: frozenset[int], mutex: Mutex | None, lm: LMSets | None = None) -> dict[int, list[int]]:
    """Landmark index ``B`` -> the indices ``A`` with ``A -> B`` reasonable (``B`` a fact landmark)."""
    n = len(sets)
    parents: dict[int, set[int]] = {}
    for a, heads in before.items():
        for b in heads:
            parents.setdefault(b, set()).add(a)
    achievers: dict[int, list[int]] = {}

    def achievers_of(i: int) -> list[int]:
        hit = achievers.get(i)
        if hit is None:
            hit = achievers[i] = first_achievers_of_set(task, sets[i], lm)
        return hit

    def isolated(f: int) -> bool:
        if mutex is None:
            return True
        return isinstance(mutex, FactMutex) and mutex.isolated(f)

    def mutex_sets(x: frozenset[int], f: int) -> bool:
        return mutex is not None and all(mutex(g, f) for g in x)

    def interferes(a: int, b: int) -> bool:
        (fb,) = sets[b]
        if fb in sets[a]:
            return False
        if isolated(fb):  # no fact is mutex with fb: only the deletes of the first achievers count
            acts = achievers_of(a)
            return bool(acts) and all(fb in task.dele[x] for x in acts)
        if mutex_sets(sets[a], fb):
            return True
        acts = achievers_of(a)
        if acts and all(fb in task.dele[x] or (mutex is not None and any(mutex(e, fb) for e in task.add[x]))
                        for x in acts):
            return True
        return any(mutex_sets(sets[p], fb) for p in parents.get(a, ()) if fb not in sets[p])

    out: dict[int, list[int]] = {}
    for b in range(n):
        if len(sets[b]) != 1:
            continue
        (fb,) = sets[b]
        if fb in goal:
            candidates = {a for a in range(n) if a != b and len(sets[a]) == 1}
        else:
            candidates = {a for c in before.get(b, ()) for a in parents.get(c, ()) if a != b}
        for a in sorted(candidates):
            if a in before.get(b, ()) or b in before.get(a, ()):
                continue  # already ordered necessarily
            if sets[a] & task.init and fb in task.init:
                continue
            if interferes(a, b):
                out.setdefault(b, []).append(a)
    return out



def landmark_sets(task: Task) -> list[frozenset[int] | None]:
    """``LM(f)`` for each fact id (``None`` where the relaxation never reaches f)."""
    nf = len(task.facts)
    lm: list[frozenset[int] | None] = [None] * nf
    for f in task.init:
        lm[f] = frozenset((f,))
    pre, add, by_pre = task.pre, task.add, task.by_pre
    order = relaxed_order(task)  # breadth first: the order in which actions become applicable
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


def fact_first_achievers(task: Task, lm: list[frozenset[int] | None], facts: frozenset[int]) -> dict[int, list[int]]:
    """Fact -> the actions that may first make it true: they add it, do not need it, are relaxed-reachable."""
    pre = task.pre
    out: dict[int, list[int]] = {}
    for a, adds in enumerate(task.add):
        if any(lm[p] is None for p in pre[a]):
            continue
        for e in adds:
            if e in facts and e not in pre[a]:
                out.setdefault(e, []).append(a)
    return out


class ReferenceLandmarkCount:
    """``evaluate(state, accepted) -> (h, preferred)``; ``accepted`` is the path's accepted set.

    Landmarks are numbered sets of facts (``sets``; the kernel also takes
    disjunctions, here each is one fact landmark, in fact order).  A landmark
    is accepted (its index in the accepted set) once one of its facts holds.
    """

    def __init__(self, task: Task, orders: bool = True) -> None:
        nactions = len(task.pre)
        mutex = task.memo.get("mutex")
        task = relaxed_task(task)  # derived facts are reached by the rules (relaxed actions of cost 0)
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
        for a, adds in enumerate(task.add[:nactions]):
            for i in sorted({i for e in adds for i in self.of_fact.get(e, ())}):
                self.achievers.setdefault(i, []).append(a)
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
        achievers = fact_first_achievers(task, lm, self.landmarks)
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
                                                             if f in task.init], lm_sets)
        for d, lm in found:
            if d in of_set:
                self.before.setdefault(of_set[d], []).append(index[lm])
                continue
            i = of_set[d] = len(self.sets)
            self.sets.append(d)
            self.before.setdefault(i, []).append(index[lm])
            acts = first_achievers_of_set(task, d)
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
