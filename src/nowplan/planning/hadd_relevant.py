"""Goal-relevant, incremental h_add: the ground additive relaxation restricted to what a call asks for.

:func:`nowplan.planning.heuristics.hadd_ids` explores every ground action of the
problem from the belief, once per planner call, although a regression search only
ever asks for the values of its goal's atoms and of the preconditions of their
achievers.  h_add of a fact is the cheapest of its achievers' costs plus the sum of
their preconditions' values, so it depends only on the facts backward-relevant to it:
its achievers, their preconditions, and so on, stopping at facts that cost 0 (true
in the belief, or a negative precondition whose atom is already false).

:class:`RelevantHadd` explores that closure when a fact is first asked for (one
batch per fact, stopping at facts an earlier batch valued, which are final and enter
as constants), with the same generalised Dijkstra as :func:`hadd_ids`, so each value
is exactly that of the full exploration.

Across the calls of one problem and level (the executive plans again after every
step, from a belief that differs in a few facts), the batches are kept
(:class:`HaddMemo`): a batch depends on the truth of the facts it examined, on the
preconditions of its actions at this call's levels and on the batches whose values
it used; a call drops the batches a changed fact or a re-levelled action touches
(and those that used them) and keeps the rest.  With an action whose cost is a
function of the belief the memo is not kept between calls.
``tests/test_hadd_relevant.py`` compares the values with :func:`hadd_ids`.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field

from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.grounding import Grounder
from nowplan.planning.ground_task import GroundTask
from nowplan.planning.heuristics import ground_task

_Pre = tuple[tuple[int, int], ...]


@dataclass
class _Batch:
    facts: list[int]
    acts: list[int]
    deps: set[int]  # facts whose truth the batch read
    used: set[int]  # batches whose values it took as constants


@dataclass
class HaddMemo:
    """h_add values of one problem at one top level, kept while the facts they read stand."""

    true_now: frozenset[int] = frozenset()
    over: dict[int, _Pre] = field(default_factory=dict)
    values: dict[int, float] = field(default_factory=dict)
    owner: dict[int, int] = field(default_factory=dict)
    batches: dict[int, _Batch] = field(default_factory=dict)
    by_fact: dict[int, set[int]] = field(default_factory=dict)
    by_act: dict[int, set[int]] = field(default_factory=dict)
    users: dict[int, set[int]] = field(default_factory=dict)
    next_id: int = 0
    current: object = None  # the RelevantHadd the memo was last synced for
    kept_batches: int = 0  # batches a sync kept (for tests and profiles)
    dropped_batches: int = 0

    def sync(self, true_now: frozenset[int], over: dict[int, _Pre]) -> None:
        """Drop what a change of belief or of the overridden actions' preconditions touches."""
        stack: list[int] = []
        for f in true_now.symmetric_difference(self.true_now):
            stack.extend(self.by_fact.get(f, ()))
        for k in over.keys() | self.over.keys():
            if over.get(k) != self.over.get(k):
                stack.extend(self.by_act.get(k, ()))
        self.true_now, self.over = true_now, over
        while stack:
            b = stack.pop()
            batch = self.batches.pop(b, None)
            if batch is None:
                continue
            self.dropped_batches += 1
            stack.extend(self.users.pop(b, ()))
            for f in batch.facts:
                del self.values[f]
                del self.owner[f]
            for f in batch.deps:
                self.by_fact[f].discard(b)
            for k in batch.acts:
                self.by_act[k].discard(b)
            for u in batch.used:
                s = self.users.get(u)
                if s is not None:
                    s.discard(b)
        self.kept_batches += len(self.batches)

    def add(self, batch: _Batch, found: dict[int, float]) -> None:
        b = self.next_id
        self.next_id += 1
        self.batches[b] = batch
        for f in batch.facts:
            self.values[f] = found.get(f, math.inf)
            self.owner[f] = b
        for f in batch.deps:
            self.by_fact.setdefault(f, set()).add(b)
        for k in batch.acts:
            self.by_act.setdefault(k, set()).add(b)
        for u in batch.used:
            self.users.setdefault(u, set()).add(b)


def _memo(task: GroundTask, top: int) -> HaddMemo:
    if not task.all_fixed:
        return HaddMemo()  # costs read the belief: nothing carries over to another call
    hit = task.memo.get(("hadd", top))
    if not isinstance(hit, HaddMemo):
        hit = task.memo[("hadd", top)] = HaddMemo()
    return hit


class RelevantHadd:
    """h_add values of fact ids, explored backward-relevantly from the facts asked for."""

    def __init__(
        self, grounder: Grounder, levels: LevelMap, drop: frozenset[str], cost: Callable[[Action], float],
        true_now: frozenset[int] | None = None,
    ) -> None:
        self.task = task = ground_task(grounder, drop)
        self.adders = task.adders()
        top = levels.top
        self.kept = task.kept(top)[0]
        self.over: dict[int, _Pre] = {}
        for k, lv in task.lowered(levels).items():
            self.over[k] = tuple((f, t) for f, c, t in task.pre[k] if c > lv)
        # the facts the belief lists (``true_now``: the caller's ids of them)
        self.true_now = true_now if true_now is not None else grounder.domain.facts.ids_of(grounder.belief.atoms())
        self.cost = cost
        self.memo = _memo(task, top)
        self.values = self.memo.values
        self._sync()

    def _sync(self) -> None:
        """Make the memo hold for this call's belief and levels (another call may have used it since)."""
        if self.memo.current is not self:
            self.memo.sync(self.true_now, self.over)
            self.memo.current = self

    def _pre(self, k: int) -> _Pre:
        p = self.over.get(k)
        return self.kept[k] if p is None else p

    def _free(self, f: int, twin: int) -> bool:
        """Costs 0: true now, or a negative precondition whose atom is already false."""
        return f in self.true_now or (twin >= 0 and twin not in self.true_now)

    def get(self, f: int) -> float:
        """h_add of fact ``f`` (``inf`` when the relaxation does not reach it)."""
        if f in self.true_now:
            return 0.0
        self._sync()
        v = self.values.get(f)
        if v is None:
            self._explore(f)
            v = self.values[f]
        return v

    def extend(self, facts: Iterable[int]) -> None:
        """Give ``facts`` their values (one batch per fact not valued yet)."""
        self._sync()
        for f in facts:
            if f not in self.values and f not in self.true_now:
                self._explore(f)

    def _explore(self, root: int) -> None:
        task, values, owner = self.task, self.values, self.memo.owner
        # backward closure: facts neither free nor valued, and the actions adding them
        facts: set[int] = set()
        acts: list[int] = []
        seen_acts: set[int] = set()
        deps = {root}
        stack = [root]
        while stack:
            f = stack.pop()
            if f in facts:
                continue
            facts.add(f)
            for k in self.adders.get(f, ()):
                if k in seen_acts:
                    continue
                seen_acts.add(k)
                acts.append(k)
                for g, t in self._pre(k):
                    deps.add(g)
                    if t >= 0:
                        deps.add(t)
                    if g not in facts and g not in values and not self._free(g, t):
                        stack.append(g)
        # generalised Dijkstra over those actions (free preconditions cost 0, valued ones their value)
        waiting: dict[int, list[int]] = {}
        missing: dict[int, int] = {}
        total: dict[int, float] = {}
        used: set[int] = set()
        fixed, effects = task.fixed_cost, task.effects
        found: dict[int, float] = {}
        queue: list[tuple[float, int, int]] = []
        tick = 0
        for k in acts:
            n = 0
            c = fixed[k]
            tk = self.cost(task.action(k)) if c is None else c
            for g, t in self._pre(k):
                if g in facts:
                    waiting.setdefault(g, []).append(k)
                    n += 1
                elif not self._free(g, t):
                    tk += values[g]
                    used.add(owner[g])
            total[k] = tk
            missing[k] = n
            if n == 0:
                for e in effects[k]:
                    if e in facts and tk < found.get(e, math.inf):
                        found[e] = tk
                        queue.append((tk, tick, e))
                        tick += 1
        heapq.heapify(queue)
        done: set[int] = set()
        while queue:
            c, _, f = heapq.heappop(queue)
            if f in done or c > found[f]:
                continue
            done.add(f)
            for k in waiting.get(f, ()):
                missing[k] -= 1
                total[k] += c
                if missing[k] == 0:
                    tk = total[k]
                    for e in effects[k]:
                        if e in facts and tk < found.get(e, math.inf):
                            found[e] = tk
                            heapq.heappush(queue, (tk, tick, e))
                            tick += 1
        self.memo.add(_Batch(sorted(facts), acts, deps, used), found)
