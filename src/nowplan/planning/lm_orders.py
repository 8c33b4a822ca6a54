"""Disjunctive landmarks and reasonable orderings for the landmark count (LAMA's landmark graph).

Two additions to the fact landmarks of :mod:`nowplan.planning.landmarks`, in
the spirit of Richter, Helmert and Westphal (RHW) and of Hoffmann, Porteous
and Sebastia's reasonable orderings as LAMA approximates them:

* **Disjunctive landmarks.**  For a fact landmark ``L`` not true initially,
  if each of its *first achievers* (actions that add ``L`` and can be applied
  before ``L`` first holds: their preconditions are reachable in the delete
  relaxation without any action that adds ``L``) needs some fact of one
  predicate, the set of those facts is a landmark: gripper's "ball b is in
  the left or in the right gripper" before "b is in room B".  Sets of more
  than :data:`MAX_DISJUNCTION` facts, sets with a fact true initially, sets
  containing a fact landmark and sets sharing a fact with a disjunctive
  landmark found before (Fast Downward's landmark graph does not let two
  disjunctive landmarks overlap) are left out.  ``D`` comes necessarily before
  ``L``, and every fact landmark that all first achievers of ``D`` need comes
  before ``D``.
* **Reasonable orderings** ``A -> B``: achieving ``B`` before ``A`` would mean
  destroying ``B`` to achieve ``A`` and making it true again.  Candidates are
  (a) ``B`` a goal fact and ``A`` any fact landmark, and (b) ``B`` necessarily
  before some landmark ``C`` that needs ``A`` too.  ``A`` *interferes* with
  ``B`` when the two are mutex, when every first achiever of ``A`` deletes
  ``B`` or adds a fact mutex with ``B``, or when a landmark that comes
  necessarily before ``A`` is mutex with ``B``.  Mutexes come from the
  domain's inferred invariants (:mod:`nowplan.planning.invariants`).

The landmark count uses a reasonable ordering as Fast Downward's status
manager does: a landmark reached while one of its reasonable predecessors is
not yet reached still counts (it will have to be reached again).  In gripper,
moving to room B with one ball no longer looks like progress while balls
that could be carried along are still in room A.
"""

from __future__ import annotations

from collections import deque
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import TYPE_CHECKING

from nowplan.planning.fact_mutex import FactMutex
from nowplan.planning.task import Task

if TYPE_CHECKING:
    from nowplan.planning._kernel import Kernel

MAX_DISJUNCTION = 4  # facts of one disjunctive landmark

Mutex = Callable[[int, int], bool]


LMSets = Sequence["frozenset[int] | None"]


def first_achievers(task: Task, facts: frozenset[int], lm: LMSets | None = None) -> list[int]:
    """Actions adding a fact of ``facts`` that are applicable in the relaxation before any fact of it holds.

    With the fact landmarks of every fact (``lm``, Zhu and Givan's sets) a
    single fact ``L`` needs no exploration: a precondition ``p`` is reachable
    without ``L`` exactly when ``L`` is not in ``LM(p)``.  ``lm`` may be the
    sets of a goal's cone only (``landmark_sets(task, goal)``) when ``L`` is a
    landmark of that goal not true now: the preconditions of its adders are
    then in the cone.
    """
    pre, add, by_pre = task.pre, task.add, task.by_pre
    if lm is not None and len(facts) == 1:
        (f,) = facts
        if f not in task.init:
            return [a for a in fact_adders(task).get(f, ())
                    if all(lm[p] is not None and f not in lm[p] for p in pre[a])]  # type: ignore[operator]
    memo = task.memo.setdefault("first_achievers", {})
    hit = memo.get(facts)
    if hit is not None:
        return list(hit)
    adders = fact_adders(task)
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


def prime_first_achievers(task: Task, families: Sequence[frozenset[int]], lm: LMSets,
                          native: Kernel | None = None) -> None:
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
    and carry no bit ``k``.  The actions the relaxation applies are those of
    :func:`relaxed_order` (``lm``, the fact landmark sets, is not read: a goal's
    cone leaves most facts out).  With ``native`` (the compiled kernel of
    ``task``'s actions) the propagation runs in C, with the same results.
    """
    memo = task.memo.setdefault("first_achievers", {})
    todo = sorted({f for f in families if f not in memo}, key=sorted)
    if not todo:
        return
    if native is not None:
        found = native.first_achievers(task.init, relaxed_order(task), [sorted(f) for f in todo])
        for fam, acts in zip(todo, found, strict=True):
            memo[fam] = tuple(acts)
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
        for a in fact_adders(task).get(f, ()):
            amask[a] |= bits
    order = relaxed_order(task)
    reachable = [False] * len(pre)  # the relaxation applies it: every precondition is reached (lm[p] is not None)
    for a in order:
        reachable[a] = True
    work = deque(order)
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
    adders = fact_adders(task)
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
        task.memo["relaxed_reached"] = frozenset(reached)
    assert isinstance(hit, list)
    return hit


def set_relaxed_order(task: Task, native: Kernel) -> None:
    """Memoise :func:`relaxed_order` and :func:`relaxed_reached` from the compiled kernel (same results);
    ``native`` is built on ``task``'s actions (its rules included)."""
    if "relaxed_order" not in task.memo:
        order, reached = native.relaxed_order(task.init)
        task.memo["relaxed_order"] = order
        task.memo["relaxed_reached"] = frozenset(reached)


def relaxed_reached(task: Task) -> frozenset[int]:
    """The facts the delete relaxation reaches (with :func:`relaxed_order`, made once per task)."""
    relaxed_order(task)
    hit = task.memo["relaxed_reached"]
    assert isinstance(hit, frozenset)
    return hit


def fact_adders(task: Task) -> dict[int, list[int]]:
    """Fact -> the actions that add it, ascending (made once per task; the lists are shared, read only).

    A task from :func:`nowplan.planning.task.build_task` brings it: kept with the
    task's structure across the executive's calls, the rows its level map
    overrides patched.
    """
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
        acts = first_achievers(task, frozenset((fact,)), lm)
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
            hit = achievers[i] = first_achievers(task, sets[i], lm)
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
    init = task.init
    singles = [a for a in range(n) if len(sets[a]) == 1]
    singles_not_now = [a for a in singles if not sets[a] & init]
    deleted_by_all: dict[int, list[int]] | None = None  # fact -> the singles all of whose achievers delete it
    touching: _Touching | None = None  # the singles that may interfere with a fact, by fact and by mutex key
    for b in range(n):
        if len(sets[b]) != 1:
            continue
        (fb,) = sets[b]
        b_now = fb in init
        if fb in goal and isolated(fb):
            # every fact landmark is a candidate, and one interferes exactly when it has first achievers
            # and each deletes fb: read from an index made once instead of testing every pair (a goal of
            # n facts, each a landmark, made this loop n^2 interference tests: 65,535 on visit-all 16x16)
            if deleted_by_all is None:
                deleted_by_all = {}
                for a in singles:
                    acts = achievers_of(a)
                    if acts:
                        for f in set(task.dele[acts[0]]).intersection(*(task.dele[x] for x in acts[1:])):
                            deleted_by_all.setdefault(f, []).append(a)
            candidates: Iterable[int] = [a for a in deleted_by_all.get(fb, ()) if a != b
                                         and not (b_now and sets[a] & init)]
        elif fb in goal:  # every fact landmark (none true now when fb is: both true now is no ordering)
            if isinstance(mutex, FactMutex):
                if touching is None:
                    touching = _touching(task, sets, singles, parents, achievers_of, mutex)
                near = _near(fb, touching, mutex)
                candidates = sorted(a for a in near if a != b and not (b_now and sets[a] & init))
            else:
                candidates = [a for a in (singles_not_now if b_now else singles) if a != b]
        else:
            candidates = sorted({a for c in before.get(b, ()) for a in parents.get(c, ()) if a != b})
        before_b = before.get(b, ())
        for a in candidates:
            if a in before_b or b in before.get(a, ()):
                continue  # already ordered necessarily
            if b_now and sets[a] & init:
                continue
            if interferes(a, b):
                out.setdefault(b, []).append(a)
    return out


# (singles by the facts their first achievers delete, singles by the mutex keys that an interference
# needs one of, the singles some parent of which has no facts: such a parent is mutex with every fact)
_Touching = tuple[dict[int, list[int]], dict[object, list[int]], list[int]]


def _touching(task: Task, sets: Sequence[frozenset[int]], singles: list[int], parents: Mapping[int, set[int]],
              achievers_of: Callable[[int], list[int]], mutex: FactMutex) -> _Touching:
    """An index of the fact landmarks ``a`` by what ``interferes(a, b)`` needs ``b``'s fact to meet.

    ``A`` interferes with ``B = {f}`` only if ``f`` is mutex with ``A``'s fact, or the first achiever
    of ``A`` (every one of them, so the first) deletes ``f`` or adds a fact mutex with ``f``, or a
    parent of ``A`` is mutex with ``f`` (so is its first fact): each of those shares a mutex key with
    ``f`` or names ``f``.  Testing only the landmarks found under ``f``'s keys and ``f`` itself gives
    the same orders as testing every pair (a goal of n facts, each a landmark in a mutex group, made
    n^2 tests: 124,750 on gripper with 250 balls).
    """
    by_fact: dict[int, list[int]] = {}
    by_key: dict[object, list[int]] = {}
    always: list[int] = []
    for a in singles:
        keys: set[object] = set()
        for f in sets[a]:
            keys |= mutex.keys(f)
        acts = achievers_of(a)
        if acts:
            x = acts[0]
            for f in task.dele[x]:
                by_fact.setdefault(f, []).append(a)
            for e in task.add[x]:
                keys |= mutex.keys(e)
        for p in parents.get(a, ()):
            if not sets[p]:
                always.append(a)
            else:
                keys |= mutex.keys(min(sets[p]))
        for k in keys:
            by_key.setdefault(k, []).append(a)
    return by_fact, by_key, always


def _near(f: int, touching: _Touching, mutex: FactMutex) -> set[int]:
    """The fact landmarks indexed under ``f`` or one of its mutex keys (see :func:`_touching`)."""
    by_fact, by_key, always = touching
    out = set(by_fact.get(f, ()))
    out.update(always)
    for k in mutex.keys(f):
        out.update(by_key.get(k, ()))
    return out

