"""The regression A*'s loop compiled (``_kernel_regress.c``), for the calls it can run.

:func:`nowplan.planning.regression_astar.astar` is the reference; the compiled loop makes the
same pre-images, orders the frontier by the same ``(f, h, r, idle, stamp)`` and keeps the same
costs, stamps and parents, so it returns the same plan with the same counters
(``tests/test_regression_native.py`` checks both on random problems).  It runs a call when

* the estimate is the ground h_add of :class:`~nowplan.planning.hadd_kernel.KernelHadd` (a
  fixed value per fact: no domain estimate, no lazy relaxation, so eager search: nothing is
  deferred) and its values are whole numbers (so a sum does not depend on its order);
* the call has no forbidden first steps and no generator that may give up, and its root goal
  is consistent (a serialized or monotonic call, ``order`` or ``protect``, runs there too);
* every fact's achievers are the problem's (no generator achieves it; where the level map puts
  some actions at other levels, the call asks every fact's templates once, as the Python loop
  does; where costs read the belief, the loop asks each action's cost once per call) and every
  fact is a plain value
  (equality rule); plain (pairwise) conflict rules are asked once per pair of facts
  (``FactTable.plain_conflict``, kept by the loop).

Otherwise :func:`run` returns ``None`` and the Python loop runs.  The facts, actions and
achievers are registered once per ground task and top level (kept in ``task.memo``): a fact's
achievers the first time a search meets it.  Where every cost is a number, the loop holds the
ground task's actions as fact ids (``use_task``), and a fact whose achievers are exactly the task's
actions adding it (:meth:`~nowplan.planning.grounding.Grounder.task_answers`) gets them there
(``task_achievers``, ``_kernel_regress_task.h``) without a Python template per action; other facts
go through the successor templates, a template that is a task action's taking its index.
``NOWPLAN_PURE_PYTHON=1`` switches it off, as it does the forward kernel.

Profile that led here (``nowplan plan --engine regression`` on generated logistics-20, seed 0,
cProfile): 84,826 successor regressions in 758 expansions; ``subgoals.regress`` 0.42 s and the
successor bookkeeping ``make`` 0.24 s of the search's 1.25 s.  Then (flat logistics-10, the search
alone, 26a303a's commit message): registering achievers through Python was 78 % of the compiled
search's CPU; through the task, 14 %.
"""

from __future__ import annotations

import bisect
import importlib
import logging
from collections.abc import Hashable, Sequence
from types import ModuleType
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Goal
from nowplan.core.facts import FactTable
from nowplan.core.operators import Action
from nowplan.planning.hadd_kernel import KernelHadd
from nowplan.planning.native import pure_python_forced
from nowplan.planning.plan import PlanStatus

if TYPE_CHECKING:
    from nowplan.planning.ground_task import GroundTask
    from nowplan.planning.regression_search import _Search
    from nowplan.planning.subgoals import ActionFacts

log = logging.getLogger(__name__)

_GAP = 1 << 12  # the room left between two facts' ranks (see Compiled._rank)
_RMIN, _RMAX = -(1 << 31), (1 << 31) - 1  # the loop keeps ranks as int32

API = 6  # REGRESS_API in _kernel_regress.c

_mod: ModuleType | None | bool = False  # not imported yet


def _module() -> ModuleType | None:
    global _mod
    if _mod is False:
        try:
            m = importlib.import_module("nowplan.planning._kernel_regress")
        except ImportError as e:
            log.debug("the regression loop's kernel is not available (%s): its Python code runs", e)
            _mod = None
        else:
            if getattr(m, "API", None) != API:
                log.debug("the regression loop's kernel is stale (API %s, expected %s; rebuild it with pip "
                          "install -e .): its Python code runs", getattr(m, "API", None), API)
                _mod = None
            else:
                _mod = m
    return _mod if isinstance(_mod, ModuleType) else None


def available() -> bool:
    """Whether the compiled loop is built and not switched off."""
    return not pure_python_forced() and _module() is not None


class Compiled:
    """One ground task's facts, actions and achievers at one top level, as the compiled loop knows them."""

    def __init__(self, mod: ModuleType, table: FactTable) -> None:
        self.mod = mod
        self.table = table
        self.loop: Any = mod.Regressor(bool(table.keyed), bool(table.plain))
        self.acts: dict[int, Action] = {}  # by index, those registered from Python (kept alive: see index)
        self.task: GroundTask | None = None  # the ground task the loop reads achievers off (use_task)
        self.pre: list[tuple[int, ...]] = []  # the task's kept preconditions at the top level
        self.index: dict[tuple[int, int], int] = {}  # (id(action), id(its facts at a level)) -> index
        self.keys: dict[Hashable, int] = {}
        self.ok = True  # False once a fact that is not a plain value is met: the Python loop runs
        # the facts in FactTable.sorted order as (sort key, id), with their ranks (ascending, with gaps)
        self._sorted: list[tuple[Any, int]] = []
        self._ranks: list[int] = []

    def sync(self) -> bool:
        """Add the facts the loop does not know yet and rank them all as ``FactTable.sorted`` does."""
        T, loop = self.table, self.loop
        n = len(T.atoms)
        start = loop.facts
        if start == n:
            return self.ok
        keys = self.keys
        for f in range(start, n):
            if not T.equality[f]:
                self.ok = False
            ids = []
            for k in T.gkeys[f]:
                i = keys.get(k)
                if i is None:
                    i = keys[k] = len(keys)
                ids.append(i)
            loop.add_fact(T.fluent[f], ids)
        self._rank(start, n)
        return self.ok

    def _rank(self, start: int, n: int) -> None:
        """Rank facts ``start..n`` among the others; the loop sorts a node's facts by rank.

        A new fact takes a rank between its neighbours' in ``FactTable.sorted`` order (ties by id,
        as that stable sort leaves them); where there is no room, or most facts are new, every fact
        is ranked again with even gaps.  (Ranking all facts on each new one was 7 % of a compiled
        search's CPU on logistics-10: a search meets new facts at most expansions.)
        """
        T, srt, ranks = self.table, self._sorted, self._ranks
        keys = T.sort_key
        if 2 * (n - start) < len(srt):
            new: list[int] = []
            for f in range(start, n):
                item = (keys[f], f)
                p = bisect.bisect_right(srt, item)
                lo = ranks[p - 1] if p > 0 else None
                hi = ranks[p] if p < len(ranks) else None
                if lo is None:
                    r = (hi if hi is not None else 0) - _GAP
                elif hi is None:
                    r = lo + _GAP
                else:
                    r = (lo + hi) // 2
                if r == lo or not _RMIN <= r <= _RMAX:
                    break  # no room here: rank all again
                srt.insert(p, item)
                ranks.insert(p, r)
                new.append(r)
            else:
                self.loop.set_rank(new, start)
                return
        srt[:] = sorted((keys[f], f) for f in range(n))
        gap = max(1, min(_GAP, _RMAX // (n + 1)))
        ranks[:] = range(0, gap * n, gap)
        rank = [0] * n
        for (_, f), r in zip(srt, ranks, strict=True):
            rank[f] = r
        self.loop.set_rank(rank)

    def use_task(self, search: _Search) -> None:
        """Give the loop the search's ground task, once (every fact it adds known), where every cost is a
        number and the task keeps the search's preconditions: facts the task answers for
        (:meth:`Grounder.task_answers`) then get their achievers there."""
        task = search._task
        if self.task is not None or task is None or not task.all_fixed or task.drop != search.drop:
            return
        top = search.levels.top
        self.pre = task.pre_at(top)
        self.loop.use_task(task.effects, self.pre, [float(c) for c in task.fixed_cost if c is not None])
        self.task = task

    def action(self, a: int) -> Action:
        """The loop's action ``a``."""
        act = self.acts.get(a)
        if act is None:
            assert self.task is not None
            act = self.acts[a] = self.task.action(self.loop.task_index(a))
        return act

    def _task_action(self, act: Action, info: ActionFacts, cost: float) -> int | None:
        """Where ``act``'s template is the ground task's (same facts, same cost), its index in the loop (one
        index per action, whichever way the loop meets it), else ``None``."""
        task = self.task
        if task is None:
            return None
        k = task.index.get(act.key)
        if (k is None or task.operators[task.op[k]] is not act.operator or info.all_effs != task.effects[k]
                or info.pre != self.pre[k] or cost != task.fixed_cost[k]):
            return None
        i: int = self.loop.add_task_action(k)
        self.acts[i] = act
        return i

    def need(self, search: _Search, goal: Goal, f: int, local: bool) -> bool:
        """Register fact ``f``'s successor templates (``False``: this call runs in Python); ``local``:
        for this call only (its level map puts some of the actions at other levels)."""
        T = self.table
        atom = T.atoms[f]
        if not self.ok or not search.grounder.shares_answer(atom):
            return False
        if not local and self.task is not None and search.grounder.task_answers(atom, self.task):
            self.loop.task_achievers(f)  # the task's actions adding f, registered in the loop
            return True
        temps = search._successors(f, lambda: goal)
        self.sync()
        out = []
        for act, info, cost in temps:
            i = self.index.get((id(act), id(info)))  # (info: kept on the action per level, so its id stays its own)
            if i is None and not local:
                i = self._task_action(act, info, cost)
                if i is not None:
                    self.index[(id(act), id(info))] = i
            if i is None:
                effs = [x for pair in info.eff_fl for x in pair]
                keys = self.keys
                ekeys: list[int] = []
                for k, e in info.eff_keys:
                    ki = keys.get(k)
                    if ki is None:
                        ki = keys[k] = len(keys)
                    ekeys += (ki, e)
                i = self.loop.add_action(effs, ekeys, info.self_clash, list(info.pre), float(cost), list(info.all_effs))
                self.index[(id(act), id(info))] = i
                self.acts[i] = act
            out.append(i)
        if local:
            self.loop.set_local_achievers(f, out)
        else:
            self.loop.set_achievers(f, out)
        return self.ok


def _compiled(search: _Search, mod: ModuleType) -> Compiled | None:
    task = search._task
    if task is None:
        return None
    key = ("regression loop", search.levels.top, search.drop)
    c = task.memo.get(key)
    if not isinstance(c, Compiled) or c.table is not search.table:
        c = Compiled(mod, search.table)
        task.memo[key] = c
    return c


def run(
    search: _Search, goal: Goal, max_nodes: int, order: Sequence[Atom] | None = None,
    protect: frozenset[Atom] = frozenset(),
) -> tuple[PlanStatus, list[tuple[Action | None, Goal]] | None, str] | None:
    """The call through the compiled loop, or ``None`` where it cannot run it (see the module docstring);
    ``order`` and ``protect`` as in :func:`~nowplan.planning.regression_astar.astar`."""
    mod = _module()
    if mod is None or pure_python_forced():
        return None
    T = search.table
    hadd = search.hadd
    if (not isinstance(hadd, KernelHadd) or callable(search.domain_h) or search.relaxed is not None
            or search.forbidden_first or search.gave_up is not None or not search.config.weight > 0):
        return None
    local = search._successors.overridden
    task = search._task
    root = T.ids_of(goal.atoms)
    if not root or not search.grounder.shares_answers or not T.consistent(root):
        return None
    pairs = search.pairs()
    packed = None
    if pairs is not None:
        packed = pairs.packed()
        if packed is None or pairs.excluded(root):
            return None  # (the Python loop: big-endian rows, or a goal it answers at once)
    order_ids = None if order is None else [T.id(a) for a in order]
    guard = list(T.ids_of(protect))
    comp = _compiled(search, mod)
    if comp is None or not comp.sync():
        return None
    comp.use_task(search)
    stop = search.now
    deadline = search.deadline
    status, nodes, acts, expanded, generated = comp.loop.search(
        list(root), hadd.values, search.fholds, lambda f: comp.need(search, goal, f, local),
        lambda: stop() > deadline, float(search.config.weight), int(max_nodes), not search.config.held_rewrites,
        order_ids, guard, local, T.plain_conflict if T.plain else None,
        None if task is None or task.all_fixed else (lambda a: search.cost(comp.action(a))), packed)
    if status == mod.UNSUPPORTED:
        return None
    search.expanded += expanded
    search.generated += generated
    if status == mod.SOLVED:
        steps: list[tuple[Action | None, Goal]] = [(None, T.goal(nodes[0]))]
        for a, prev in zip(acts, nodes[1:], strict=True):
            steps.append((comp.action(a), T.goal(prev)))
        return PlanStatus.SOLVED, steps, ""
    if status == mod.NODE_LIMIT:
        return PlanStatus.NODE_LIMIT, None, f"expanded {max_nodes} nodes without a plan"
    if status == mod.TIME_LIMIT:
        return PlanStatus.TIME_LIMIT, None, f"time limit of {search.config.time_limit:g} s reached"
    return PlanStatus.UNSOLVABLE, None, "search space exhausted: no plan at this level"
