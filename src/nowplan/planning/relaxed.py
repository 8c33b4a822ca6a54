"""Relaxed costs explored on demand, over the achievers the grounder finds (h_add, h_max, h_FF, LM-cut).

:class:`LazyRelaxed` estimates a subgoal from the current belief in the
delete relaxation: a fact that holds costs 0 (a fact of a predicate with a
test holds if the test says so), any other the cheapest achiever's cost
plus the sum (h_add) or the maximum (h_max) of its kept preconditions'
costs.  h_FF adds the costs of the union of the facts' relaxed plans (best
supporters by h_add, so an action two facts need is counted once); LM-cut
(Helmert & Domshlak 2009) sums the costs of disjoint action landmarks found
by repeated h_max cuts.

The achievers are the search's own (``achievers(f, context)``: the
grounder's, at the actions' levels), found on demand: asking for a fact
explores backwards from it until facts that hold, and the new achievers'
costs are propagated (label-correcting, cheapest first).  Nothing needs the
whole ground task, so it works with generators and tested predicates.

Generators see a goal, and what they give may depend on it: the
relaxation shows them the facts asked for together (the preconditions of
the action that needs the fact, or the subgoal first estimated).  For a
fact whose achievers read the goal (``context_key(f, context)`` is not
``None``) the exploration is repeated for every new reading met while
exploring (with ``recontext``, also for every subgoal estimated), and the
estimate is over the union of all achievers found so far: a fact's cost only
decreases as contexts are seen.  A fact the relaxation does not reach is a
dead end (``inf``) when no fact behind it had achievers that read the goal;
otherwise it costs ``unknown`` (0: nothing is known about it).

With every achiever found (no generators that read the goal) h_max and
LM-cut are admissible; h_add and h_FF are not.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Hashable, Iterable

from nowplan.core.operators import Action
from nowplan.planning.lmcut_lazy import lmcut_part

# a relaxed achiever of a fact: the action, its cost and its kept preconditions' fact ids
Supporter = tuple[Action, float, tuple[int, ...]]
AchieversFn = Callable[[int, frozenset[int]], list[Supporter]]
ContextKeyFn = Callable[[int, frozenset[int]], Hashable | None]

KINDS = ("add", "max", "ff", "lmcut")


class LazyRelaxed:
    """Relaxed costs of facts (see the module docstring)."""

    def __init__(
        self,
        achievers: AchieversFn,
        holds: Callable[[int], bool],
        kind: str = "add",
        context_key: ContextKeyFn | None = None,
        unknown: float = 0.0,
        recontext: bool = False,
        park: bool = False,
        maybe_zero: Callable[[int], bool] | None = None,
    ) -> None:
        if kind not in KINDS:
            raise ValueError(f"relaxed estimate {kind!r}: use add, max, ff or lmcut")
        self.achievers = achievers
        self.holds = holds
        self.kind = kind
        self.context_key = context_key
        self.unknown = unknown
        self.recontext = recontext
        # h_max / LM-cut only: leave out achievers dominated while exploring (see _unparked)
        self.park = park and kind in ("max", "lmcut")
        self._parked: dict[int, tuple[int, Supporter]] = {}  # id(action) -> (its one target, its supporter)
        # can fact f cost 0 (it holds, or an operator of cost 0 may make it)? None: any fact may
        self.maybe_zero = maybe_zero
        self._reopened = False  # a parked achiever was registered for an old fact (see _register)
        self.parked_count = 0
        self.val: dict[int, float] = {}  # facts reached so far (others explored: inf)
        self._zero: set[int] = set()  # the facts of val that cost 0 (they hold, or 0-cost steps make them)
        self.sup: dict[int, int] = {}  # best supporter of a reached fact that does not hold
        self._seen: set[int] = set()  # facts explored (in some context)
        self._dependent: set[int] = set()  # explored facts whose achievers read the goal
        self._contexts: set[tuple[int, Hashable]] = set()
        self._dead: set[int] = set()  # proven dead ends
        self._index: dict[int, int] = {}  # id(action) -> index
        self._acts: list[Action] = []  # (keeps the actions alive while their ids are keys)
        self._cost: list[float] = []
        self._pre: list[tuple[int, ...]] = []
        self._targets: list[list[int]] = []
        self._users: dict[int, list[int]] = {}
        self._achieved_by: dict[int, list[int]] = {}
        self._plans: dict[int, frozenset[int]] = {}
        self._cuts: dict[frozenset[int], float] = {}  # LM-cut per set of unmet facts (while costs stand)
        self._closures: dict[int, frozenset[int]] = {}
        self.facts_explored = 0
        self.cut_hits = 0

    # -- queries ---------------------------------------------------------------
    def value(self, f: int, context: frozenset[int] = frozenset()) -> float:
        """The relaxed cost of ``f`` (``context``: the facts asked for with it, for generators)."""
        self._ensure(f, context or frozenset((f,)))
        return self._final(f)

    def estimate(self, fs: frozenset[int]) -> float:
        seen, dependent, recontext = self._seen, self._dependent, self.recontext
        rest = fs.difference(self._zero)  # (a fact that costs 0 is never explored again)
        need = rest.difference(seen) if not recontext else {f for f in rest if f not in seen or f in dependent}
        if need:
            for f in fs:  # in fs's order, as the exploration's order may tell in ties
                if f in need:
                    self._ensure(f, fs)  # (it returns at once on a fact explored since)
        if self.kind == "lmcut":
            return self.lmcut(fs)
        if self.kind == "max":
            top = 0.0
            for f in fs.difference(self._zero):
                v = self._final(f)
                if v > top:
                    top = v
            return top
        if self.kind == "ff":
            acts: set[int] = set()
            extra = 0.0
            for f in fs:
                v = self._final(f)
                if v == math.inf:
                    return v
                if f not in self.val:
                    extra += v
                elif v > 0.0:
                    acts |= self.plan_of(f)
            return extra + float(sum(self._cost[a] for a in acts))
        total = 0.0
        for f in fs:  # (in fs's order: a float sum)
            total += self._final(f)
        return total

    def lmcut(self, fs: frozenset[int]) -> float:
        """Helmert and Domshlak's LM-cut over the explored achievers of ``fs``'s facts.

        Repeatedly: h_max with the current costs, the cut of actions leading
        from the facts that hold into the goal zone of the justification graph
        (each action's most expensive precondition), add the cheapest cost in
        the cut and take it off every action of the cut.  Admissible where
        h_max is; facts not reached and not proven dead count 0.  Ties are
        broken by fact id throughout, so equal sets of facts get equal values
        whatever order they were built in (the cuts are kept per set).
        """
        val = self.val
        goal: list[int] = []
        for f in fs.difference(self._zero):  # (the goal is sorted below)
            v = val.get(f)
            if v is None:  # not reached: dead (no estimate) or unknown (counts 0)
                if self._final(f) == math.inf:
                    return math.inf
            elif v > 0.0:
                goal.append(f)
        if not goal:
            return 0.0
        goal.sort()  # by fact id: the cut's choice among equally costly goal facts does not follow set order
        key = frozenset(goal)
        hit = self._cuts.get(key)
        if hit is not None:
            self.cut_hits += 1
            return hit
        # facts whose explored achievers share no action are independent: LM-cut adds up over them
        total = 0.0
        for part in self._parts(goal):
            pk = frozenset(part)
            known = self._cuts.get(pk)
            if known is None:
                known = self._cuts[pk] = self._lmcut(part)
            else:
                self.cut_hits += 1
            total += known
        self._cuts[key] = total
        return total

    def _parts(self, goal: list[int]) -> list[list[int]]:
        """``goal``'s facts grouped so that no two groups' relevant actions overlap."""
        if len(goal) == 1:
            return [goal]
        owner: dict[int, int] = {}  # action -> the group that needs it
        group = list(range(len(goal)))

        def find(i: int) -> int:
            while group[i] != i:
                group[i] = group[group[i]]
                i = group[i]
            return i

        for i, f in enumerate(goal):
            for a in self._closure(f):
                j = owner.setdefault(a, i)
                if j != i:
                    ri, rj = find(i), find(j)
                    if ri != rj:
                        group[ri] = rj
        parts: dict[int, list[int]] = {}
        for i, f in enumerate(goal):
            parts.setdefault(find(i), []).append(f)
        return list(parts.values())

    def _closure(self, f: int) -> frozenset[int]:
        """The actions that can fire behind ``f`` (kept until new achievers are found)."""
        hit = self._closures.get(f)
        if hit is None:
            hit = self._closures[f] = frozenset(self._relevant([f])[1])
        return hit

    def _lmcut(self, goal: list[int]) -> float:
        return lmcut_part(self, goal)

    def _relevant(self, goal: list[int]) -> tuple[set[int], list[int], list[int]]:
        """The facts behind ``goal``, the actions achieving them that can fire, and the facts that hold."""
        val = self.val
        facts, stack = set(goal), list(goal)
        acts: list[int] = []
        seen: set[int] = set()
        init: list[int] = []
        while stack:
            f = stack.pop()
            if self.holds(f):
                init.append(f)
                continue
            for a in self._achieved_by.get(f, ()):
                if a in seen:
                    continue
                pre = self._pre[a]
                if any(p not in val for p in pre):
                    continue  # never fires
                seen.add(a)
                acts.append(a)
                for p in pre:
                    if p not in facts:
                        facts.add(p)
                        stack.append(p)
        return facts, acts, init

    def plan_of(self, f: int) -> frozenset[int]:
        """The actions of ``f``'s relaxed plan (best supporters, recursively)."""
        hit = self._plans.get(f)
        if hit is not None:
            return hit
        stack = [f]
        while stack:  # post-order without recursion (chains can be long)
            g = stack[-1]
            if g in self._plans:
                stack.pop()
                continue
            a = self.sup.get(g)
            if a is None:
                self._plans[g] = frozenset()
                stack.pop()
                continue
            todo = [p for p in self._pre[a] if p not in self._plans]
            if todo:
                stack.extend(todo)
                continue
            out = {a}
            for p in self._pre[a]:
                out |= self._plans[p]
            self._plans[g] = frozenset(out)
            stack.pop()
        return self._plans[f]

    def dead(self, f: int) -> bool:
        """Is ``f`` unreachable whatever the goal shown to generators (nothing behind it read it)?"""
        if f in self._dead:
            return True
        if f in self.val:
            return False
        todo, seen = [f], {f}
        while todo:
            g = todo.pop()
            if g in self._dependent:
                return False
            for a in self._achievers_of(g):
                for p in self._pre[a]:
                    if p not in self.val and p not in seen:
                        seen.add(p)
                        todo.append(p)
        self._dead |= seen
        return True

    def known(self, f: int) -> float:
        """``f``'s cost as explored so far, without exploring: 0 if not reached, ``inf`` if dead.

        Every estimate that counts ``f`` gives at least this (h_max, LM-cut and
        h_add are at least the largest cost of a fact they count) while the
        costs stand; they only fall as more is explored.
        """
        v = self.val.get(f)
        if v is not None:
            return v
        return math.inf if f in self._seen and self.dead(f) else 0.0

    # -- internals -------------------------------------------------------------
    def _final(self, f: int) -> float:
        v = self.val.get(f)
        if v is not None:
            return v
        return math.inf if self.dead(f) else self.unknown

    def _achievers_of(self, g: int) -> Iterable[int]:
        return self._achieved_by.get(g, ())

    def _ensure(self, f: int, context: frozenset[int]) -> None:
        if f not in self._seen:
            if f not in self._users and self.holds(f):
                # a fact that holds, asked for first: it costs 0 and no explored action waits for it
                # (what _explore would do; a subgoal holds many such facts)
                self._seen.add(f)
                self.facts_explored += 1
                self.val[f] = 0.0
                self._zero.add(f)
                return
        elif f not in self._dependent or not self.recontext:
            return
        if f in self.val and self.val[f] == 0.0:
            return
        if f in self._seen:
            key = self.context_key(f, context) if self.context_key is not None else None
            if key is None or (f, key) in self._contexts:
                return
        self._explore(f, context)

    def _register(self, sup: Supporter, target: int, fresh: list[int]) -> int:
        act, c, pre = sup
        k = id(act)
        a = self._index.get(k)
        if a is None:
            a = self._index[k] = len(self._acts)
            self._acts.append(act)
            self._cost.append(c)
            pre = tuple(dict.fromkeys(pre))
            self._pre.append(pre)
            self._targets.append([])
            for p in pre:
                self._users.setdefault(p, []).append(a)
        tg = self._targets[a]
        if target not in tg:
            tg.append(target)
            self._achieved_by.setdefault(target, []).append(a)
            fresh.append(a)
        parked = self._parked.pop(k, None) if self._parked else None
        if parked is not None and parked[0] not in tg:  # the fact it was left out for gets it back
            tg.append(parked[0])
            self._achieved_by.setdefault(parked[0], []).append(a)
            self._reopened = True
        return a

    def _unparked(self, f: int, sups: list[Supporter]) -> list[Supporter]:
        """``f``'s achievers to register now; the others wait, parked, until an exploration needs them.

        Let ``a`` be the first cheapest achiever of ``f`` whose preconditions all
        hold.  An achiever ``b`` that is not registered yet, costs more than
        ``a`` (or as much, listed after it or with a precondition that cannot
        cost 0, ``maybe_zero``) and is parked for no other fact is parked:
        neither registered nor its preconditions explored.  (So ``b`` is never
        the first cheapest achiever with preconditions of cost 0 that
        :func:`~nowplan.planning.lmcut_lazy.cut_graph` keeps.)  ``f`` then
        costs ``a``'s cost in h_max whatever ``b`` gives, and in LM-cut's pruned
        graph (:func:`~nowplan.planning.lmcut_lazy.cut_graph`) ``b`` would be
        left out as dominated by an achiever no more costly with preconditions
        of cost 0 and ``b``'s one target among its own.  As soon as ``b`` is
        asked for by another fact (registered there, or parked a second time)
        it is registered for ``f`` too and its preconditions are explored, so
        every action the pruned graph keeps is registered with all its targets
        as in the whole exploration: the values are the whole exploration's
        (``tests/test_relaxed_parking.py`` compares them).  This keeps the
        exploration of a vehicle's door, which unloading any package frees,
        from exploring every package.
        """
        holds = self.holds
        best, bc = -1, math.inf
        for i, (_, c, pre) in enumerate(sups):
            if c < bc and all(holds(p) for p in pre):
                best, bc = i, c
        if best < 0:
            return sups
        out: list[Supporter] = []
        parked, index, zero = self._parked, self._index, self.maybe_zero
        for i, sup in enumerate(sups):
            c = sup[1]
            k = id(sup[0])
            if i == best or c < bc or k in index or (
                    c == bc and i < best and (zero is None or all(zero(p) for p in sup[2]))):
                out.append(sup)
                continue
            prev = parked.get(k)
            if prev is not None and prev[0] != f:
                out.append(sup)  # parked for another fact: registered now (and for that fact, in _register)
                continue
            if prev is None:
                parked[k] = (f, sup)
                self.parked_count += 1
        return out

    def _explore(self, f0: int, context: frozenset[int]) -> None:
        fresh: list[int] = []  # actions with a new target
        reached: list[int] = []  # facts that hold, newly seen
        old = False  # achievers added to a fact seen before (a new context of a dependent one)
        stack = [(f0, context)]
        while stack:
            f, ctx = stack.pop()
            first = f not in self._seen
            if first:
                self._seen.add(f)
                self.facts_explored += 1
                if self.holds(f):
                    reached.append(f)
                    continue
            elif f not in self._dependent:
                continue
            key = self.context_key(f, ctx) if self.context_key is not None else None
            if key is not None:
                if (f, key) in self._contexts:
                    continue
                self._contexts.add((f, key))
                self._dependent.add(f)
            elif not first:
                continue
            old = old or not first
            sups = self.achievers(f, ctx)
            if self.park and len(sups) > 1:
                sups = self._unparked(f, sups)
            for sup in sups:
                a = self._register(sup, f, fresh)
                pre = self._pre[a]
                pctx: frozenset[int] | None = None
                for p in pre:
                    if p not in self._seen or p in self._dependent:
                        if pctx is None:
                            pctx = frozenset(pre)
                        stack.append((p, pctx))
        if self._reopened:  # achievers added to facts seen before: their cuts and closures change
            self._reopened = False
            old = True
        self._propagate(reached, fresh, old)

    def _propagate(self, reached: list[int], fresh: list[int], old: bool = True) -> None:
        val = self.val
        heap: list[tuple[float, int, int, int]] = []
        tick = 0
        for f in reached:
            if f not in val:
                val[f] = 0.0
                self._zero.add(f)
                heap.append((0.0, tick, f, -1))
                tick += 1
        for a in fresh:
            v = self._action_value(a)
            if v < math.inf:
                for t in self._targets[a]:
                    if v < val.get(t, math.inf):
                        heap.append((v, tick, t, a))
                        tick += 1
        # Achievers of facts seen for the first time change nothing behind the facts seen
        # before (their achievers' preconditions were all explored with them): their costs,
        # cuts, plans and closures stand.  Achievers added to an old fact change them.
        if old and (fresh or reached):
            self._plans.clear()
            self._cuts.clear()
            self._closures.clear()
        if not heap:
            return
        heapq.heapify(heap)
        while heap:
            v, _, f, a = heapq.heappop(heap)
            if a >= 0:
                if v >= val.get(f, math.inf):
                    continue
                val[f] = v
                self.sup[f] = a
                if v == 0.0:
                    self._zero.add(f)
            for u in self._users.get(f, ()):
                x = self._action_value(u)
                if x < math.inf:
                    for t in self._targets[u]:
                        if x < val.get(t, math.inf):
                            heapq.heappush(heap, (x, tick, t, u))
                            tick += 1

    def _action_value(self, a: int) -> float:
        val = self.val
        x = 0.0
        if self.kind in ("max", "lmcut"):
            for p in self._pre[a]:
                v = val.get(p)
                if v is None:
                    return math.inf
                if v > x:
                    x = v
        else:
            for p in self._pre[a]:
                v = val.get(p)
                if v is None:
                    return math.inf
                x += v
        return self._cost[a] + x
