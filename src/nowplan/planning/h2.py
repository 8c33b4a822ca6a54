"""Pairs of facts no reachable state holds together (h² mutexes), to prune regression's subgoals.

Regression meets subgoals no state reaches: an abstract level of a hierarchy drops the
preconditions that would have said so (the held-out gridfix: a van with a full battery away from
every dock, where charging is at docks and every drive spends a level), and a flat search makes
them too (HSPr, Bonet & Geffner 2001; Haslum & Geffner 2000 for h^m).  :class:`PairReach`
computes, over a problem's ground task, the facts and pairs of facts reachable in the h²
relaxation of the concrete problem (every precondition kept, whatever the level): a pair is
reachable if a state where the search may start holds both, or an action adds both, or an
action adds one and keeps the other (neither deletes it nor adds a fact a conflict rule excludes
it with) while the other is reachable with each of the action's preconditions, whose pairs are
all reachable.  That over-approximates the pairs true together in some reachable state, so a
subgoal holding a pair outside it is reached by no plan: the search drops it (sound at every
level: each pre-image of an abstract plan becomes a goal of a concrete call).

Only positive facts of boolean predicates without tests take part (the *participants*); a
precondition on anything else (a negative literal, a tested or derived predicate) is taken to
hold, and a subgoal's facts outside the participants are never part of a pruned pair.  The
start is every fact the belief lists and, where the belief is unsure of a fluent
(:class:`~nowplan.belief.protocols.HasUnknowns`), its positive value too, each with every other:
pairs across possible worlds are kept (an over-approximation, so still sound).  The table is
kept with the ground task and shared by the problem's calls; a call whose start holds a pair
the table does not (an exogenous change, a new belief) adds it and runs the fixpoint again, so
the table only grows and stays sound for every start it has been asked from.

Pairs are Python integers as bitsets (``reach[f]``: the facts reachable with ``f``).  The
fixpoint sweeps the actions until nothing changes; each sweep costs a few big-integer operations
per action.  Tasks above ``MAX_FACTS`` participants or ``MAX_ACTIONS`` actions are not computed
(the planner runs without the pruning; :func:`pair_reach` returns ``None``).
"""

from __future__ import annotations

import logging
import sys
from array import array
from collections.abc import Iterable
from typing import Any

from nowplan.belief.protocols import HasUnknowns, offers
from nowplan.core.atoms import Atom
from nowplan.core.domain import Domain
from nowplan.planning.ground_task import GroundTask

log = logging.getLogger(__name__)

MAX_FACTS = 6_000
MAX_ACTIONS = 60_000
MAX_PLAIN = 120  # participants up to which plain conflict rules add deletes (asked per pair of facts: ~20 ms)
MAX_SWEEPS = 10_000  # sweeps of one fixpoint (4-13 on the classical instances); past it nothing is pruned


class PairReach:
    """The h²-reachable facts and pairs of one ground task (see the module docstring)."""

    def __init__(self, task: GroundTask, domain: Domain) -> None:
        T = task.table
        self.table = T
        preds = domain.predicates
        derived = domain.derived

        def takes_part(f: int) -> bool:
            a = T.atoms[f]
            p = preds.get(a.predicate)
            return (a.value is True and p is not None and p.boolean and p.test is None
                    and a.predicate not in derived and a.predicate not in task.drop)

        self.bit: dict[int, int] = {}  # participant fact -> its bit
        self.mask: dict[int, int] = {}  # participant fact -> 1 << its bit
        self.fact_of: list[int] = []  # bit index -> fact
        acts: list[tuple[int, int, int, tuple[int, ...]]] = []  # (pre bits, add bits, delete bits, adds)
        for k in range(task.n):
            pre = 0
            for f, _c, _t in task.pre[k]:
                if takes_part(f):
                    pre |= self._bit(f)
            add, dele, adds = 0, 0, []
            for e in task.effects[k]:
                a = T.atoms[e]
                if a.value is False:
                    pos = T.by_key.get((a.predicate, a.args, True))
                    if pos is not None and takes_part(pos):
                        dele |= self._bit(pos)
                elif takes_part(e):
                    add |= self._bit(e)
                    adds.append(self.bit[e])
            acts.append((pre, add, dele, tuple(adds)))
        self._acts = acts
        self._conflict_dels()
        self.reach: list[int] = [0] * len(self.fact_of)  # per bit: the bits reachable with it
        self.facts = 0  # the reachable bits
        self.sweeps = 0
        self.version = 0  # the number of fixpoints run (the table grows with each)
        self._packed: tuple[int, tuple[bytes, bytes, bytes, int]] | None = None

    def _bit(self, f: int) -> int:
        b = self.bit.get(f)
        if b is None:
            b = self.bit[f] = len(self.fact_of)
            self.mask[f] = 1 << b
            self.fact_of.append(f)
        return 1 << b

    def _conflict_dels(self) -> None:
        """Add to each action's deletes the participants a conflict rule excludes with one of its adds."""
        T = self.table
        if not T.has_conflicts:
            return
        by_key: dict[Any, int] = {}
        for b, f in enumerate(self.fact_of):
            for key in T.gkeys[f]:
                by_key[key] = by_key.get(key, 0) | (1 << b)
        # plain (pairwise) rules are asked per pair of facts: skipped on large tasks (fewer deletes, so a
        # table that knows fewer mutexes, still sound)
        plain = bool(T.plain) and len(self.fact_of) <= MAX_PLAIN
        excl: dict[int, int] = {}  # per added bit: the participants its rules exclude (asked once per fact)
        out = []
        for pre, add, dele, adds in self._acts:
            for b in adds:
                x = excl.get(b)
                if x is None:
                    f, x = self.fact_of[b], 0
                    for key in T.gkeys[f]:
                        x |= by_key[key]
                    if plain:
                        for b2, g in enumerate(self.fact_of):
                            if b2 != b and T.plain_conflict(f, g):
                                x |= 1 << b2
                    x = excl[b] = x & ~(1 << b)
                dele |= x
            out.append((pre, add, dele & ~add, adds))
        self._acts = out

    # -- building ---------------------------------------------------------------------------
    def start_from(self, facts: Iterable[int]) -> bool:
        """Make the table hold every pair of ``facts`` (a start of the search); ``True`` if it grew."""
        bits = 0
        for f in facts:
            b = self.bit.get(f)
            if b is not None:
                bits |= 1 << b
        reach = self.reach
        grew = False
        rest = bits
        while rest:
            low = rest & -rest
            b = low.bit_length() - 1
            rest ^= low
            if bits & ~reach[b]:
                reach[b] |= bits
                grew = True
        if grew or bits & ~self.facts:
            self.facts |= bits
            self._fixpoint()
            return True
        return False

    def _fixpoint(self) -> None:
        """Sweep the actions until no pair is added.  After the first sweep an action is evaluated
        again only when the row of one of its preconditions grew since the sweep before (semi-naive:
        otherwise it would add what it added already); one without preconditions, always."""
        self.version += 1
        reach = self.reach
        dirty_last = -1  # every bit: the first sweep evaluates every action
        for _ in range(MAX_SWEEPS):
            changed = False
            dirty = 0  # the bits whose row grows in this sweep
            self.sweeps += 1
            for pre, add, dele, adds in self._acts:
                if pre & ~self.facts or (pre and not pre & (dirty_last | dirty)):
                    continue
                keep = self.facts
                rest = pre
                while rest:
                    low = rest & -rest
                    keep &= reach[low.bit_length() - 1]
                    rest ^= low
                if pre & ~keep:  # two preconditions not reachable together
                    continue
                new = (keep & ~dele) | add
                for b in adds:
                    delta = new & ~reach[b]
                    if not delta:
                        continue
                    changed = True
                    reach[b] |= delta
                    low_b = 1 << b
                    dirty |= delta | low_b
                    while delta:  # the other half of each new pair
                        low = delta & -delta
                        reach[low.bit_length() - 1] |= low_b
                        delta ^= low
                if add & ~self.facts:
                    self.facts |= add
                    changed = True
            if not changed:
                return
            dirty_last = dirty
        # (each sweep adds a fact or a pair, so the sweeps are bounded by their number; past this many,
        # the table gives up soundly: every pair reachable, nothing pruned)
        log.info("h2 pruning off: the fixpoint took more than %d sweeps", MAX_SWEEPS)
        every = (1 << len(self.fact_of)) - 1
        self.facts = every
        self.reach = [every] * len(self.fact_of)

    # -- asking -----------------------------------------------------------------------------
    def bits_of(self, fs: Iterable[int]) -> int:
        get = self.mask.get
        out = 0
        for f in fs:
            m = get(f)
            if m is not None:
                out |= m
        return out

    def excluded(self, fs: Iterable[int], new: Iterable[int] | None = None) -> bool:
        """Does ``fs`` hold a participant no state reaches, or a pair of them no state holds together?

        ``new``: only pairs with one of these facts are asked (the others were asked before)."""
        fs = list(fs)
        bits = self.bits_of(fs)
        if not bits:
            return False
        if bits & ~self.facts:
            return True
        get, reach = self.bit.get, self.reach
        for f in (fs if new is None else new):
            b = get(f)
            if b is not None and bits & ~reach[b]:
                return True
        return False

    def packed(self) -> tuple[bytes, bytes, bytes, int] | None:
        """The table for the compiled regression loop: per fact id its bit or -1 (int32, the host's
        order), per bit its row of reachable bits and the reachable bits (``w`` 64-bit words each),
        ``w``; ``None`` on a big-endian host (the rows are little-endian: the Python loop runs)."""
        if sys.byteorder != "little":
            return None
        if self._packed is None or self._packed[0] != self.version:
            w = max(1, (len(self.fact_of) + 63) // 64)
            bits = array("i", [-1]) * (max(self.fact_of, default=-1) + 1)
            for f, b in self.bit.items():
                bits[f] = b
            n = w * 8
            rows = b"".join(r.to_bytes(n, "little") for r in self.reach)
            self._packed = (self.version, (bits.tobytes(), rows, self.facts.to_bytes(n, "little"), w))
        return self._packed[1]

    def mutex(self, f: int, g: int) -> bool:
        """Are participants ``f`` and ``g`` never true together (``False`` where either does not take part)?"""
        bf, bg = self.bit.get(f), self.bit.get(g)
        if bf is None or bg is None:
            return False
        return not (self.reach[bf] >> bg) & 1

    def atoms_mutex(self, a: Atom, b: Atom) -> bool:
        return self.mutex(self.table.id(a), self.table.id(b))


def start_facts(table: Any, belief: Any, true_ids: Iterable[int]) -> set[int]:
    """The facts a search from ``belief`` may start with: those it lists, and the positive value of
    each fluent it is unsure of."""
    out = set(true_ids)
    if offers(belief, HasUnknowns):
        for pred, args in belief.unknowns():
            out.add(table.id_of(pred, args, True))
    return out


def pair_reach(task: GroundTask, domain: Domain) -> PairReach | None:
    """The task's table (kept in ``task.memo``), or ``None`` where the task is too large for it."""
    hit = task.memo.get("h2")
    if hit is None:
        if task.n > MAX_ACTIONS:
            log.info("h2 pruning off: %d ground actions (more than %d)", task.n, MAX_ACTIONS)
            hit = task.memo["h2"] = False
        else:
            pr = PairReach(task, domain)
            if len(pr.fact_of) > MAX_FACTS:
                log.info("h2 pruning off: %d facts (more than %d)", len(pr.fact_of), MAX_FACTS)
                hit = task.memo["h2"] = False
            else:
                hit = task.memo["h2"] = pr
    return hit if isinstance(hit, PairReach) else None
