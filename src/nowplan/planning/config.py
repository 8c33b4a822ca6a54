"""The regression planner's settings (:class:`PlannerConfig`) and the clock they choose.

:class:`PlannerConfig` configures :func:`nowplan.planning.regression.plan`
and, through ``engine``, the forward engine it may hand a flat call to.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Literal

from nowplan.core.atoms import Goal


@dataclass(frozen=True)
class PlannerConfig:
    """Settings of the regression planner (budgets, heuristic, search options)."""

    max_nodes: int = 50_000  # expansions for the full search
    # expansions of the forward search (None: ``max_nodes``); ``nowplan plan`` sets a far larger one, so
    # that its time limit, not the regression search's node budget, ends a forward search
    forward_max_nodes: int | None = None
    time_limit: float = 60.0  # seconds for one call (all methods), on ``clock``
    # "wall" (elapsed time) or "cpu" (this process's CPU time: the same searches end on a loaded
    # machine as on a quiet one, for experiments)
    clock: Literal["wall", "cpu"] = "wall"
    weight: float = 1.0  # f = g + weight * h
    # a regression call whose full search spends its nodes without a plan searches once more with this
    # weight (0: not), within max_nodes again: a greedier search finds a plan where the (already
    # inadmissible) h_add A* exhausts its budget; the `flat` strategy sets 5
    retry_weight: float = 0.0
    serialization: bool = True  # HPN shortcut 1
    monotonic: bool = True  # HPN shortcut 2
    shortcut_nodes: int = 2_000  # expansions allowed to each shortcut
    max_generator_values: int = 8
    seed: int = 0
    # hadd | hmax | hff | lmcut: relaxed costs from the belief (HSPr-style; h_max and LM-cut admissible);
    # count: unmet atoms x cheapest cost.
    # Without lazy_relaxation the relaxed ones need the whole ground task (a belief that lists its
    # facts, no generators or tested predicates) and fall back to count otherwise.
    heuristic: str = "hadd"
    # relax over the achievers the grounder finds, explored on demand from the subgoals' atoms
    # (works with generators and tested predicates; heuristics.LazyRelaxed)
    lazy_relaxation: bool = False
    # the estimate for the random-serialization shortcut (None: ``heuristic``); e.g. h_max there, where
    # one conjunct at a time is searched, and LM-cut for the searches of whole conjunctions
    shortcut_heuristic: str | None = None
    # "auto": search forward (nowplan.planning.forward) where the belief lists its facts and the
    # domain has no generators or tested predicates, else regress; "forward" | "regression" force one
    engine: Literal["auto", "forward", "regression"] = "auto"
    # the forward search: LAMA's first iteration (h_FF and landmark count; the default: within 2x of
    # lama-first's wall time and 10 % of its cost on more of benchmarks/classical than gbfs), lazy
    # greedy best-first on h_FF alone, or (weighted) A*
    search: Literal["gbfs", "lama", "astar"] = "lama"
    # anytime improvement after the first forward plan (weighted A* with falling weights, bounded by
    # the best cost, then plan neighborhood search): a work budget of improve x the first search's
    # expansions + forward.IMPROVE_BASE units (planning/anytime.py); 0 = off
    improve: float = 0.0
    forward_heuristic: Literal["ff", "add", "max"] = "ff"
    # action costs as the forward heuristic sees them (FD's adapt_costs): one | plusone | normal
    cost_type: Literal["one", "plusone", "normal"] = "plusone"
    # regress facts that hold through zero-cost operators into other facts that hold (a "pure
    # rewrite": same cost, same unmet facts, e.g. a held same_city(p, v) into the at(p, l) it is
    # inferred from).  Needed only by plans that undo such a fact and make it true again.  They come
    # last among equal (f, h) (planning/rewrites.py), yet below the optimal f (a weak estimate) A* still
    # meets every subset of the held facts rewritten (2^k copies of each subgoal).  False leaves them
    # out (RCHPN's joint searches, acting/peephole.py)
    held_rewrites: bool = True
    # expansions of one call over all its attempts (shortcuts and full search); 0: each attempt has
    # its own budget (shortcut_nodes, max_nodes) only.  RCHPN bounds the searches below a combined step
    # with it, so a refinement that fails costs one budget, not one per attempt
    call_nodes: int = 0
    # the forward engine grounds the operators relevant to the call's goal and to this one (None: the
    # call's goal only); the executive sets its problem's goal, so that its calls share one grounding
    # (planning/relevance.py)
    relevant_to: Goal | None = None
    # forward search at an abstract level: an action that hides preconditions costs its own cost plus
    # h_max of the hidden ones from the call's state (planning/hidden_costs.py); `nowplan run
    # --criticality auto` sets it, hand-written hierarchies keep their actions' own costs
    hidden_costs: bool = False
    # reorder a solved plan at an abstract level so that consecutive steps ask the same of the
    # preconditions the level hides (planning/regroup.py: deorder, then relinearize); the `regroup`
    # switch and `nowplan run --criticality auto` set it
    regroup: bool = False
    # the regression engine's plans are trimmed of steps the rest does not need (planning/prune.py:
    # greedy elimination checked by regression); the forward engine trims its own by replay
    prune: bool = True
    # regression drops a subgoal holding two facts no state reachable from the call's start holds
    # together (planning/h2.py: h² over the concrete ground task); None: off in a plan() call, and in
    # the executive on where the strategy plans flat (parse_strategy), off with HPN; the `h2` and
    # `noh2` switches, `nowplan plan` (on unless --no-mutexes)
    h2: bool | None = None



def _clock(config: PlannerConfig) -> Callable[[], float]:
    if config.clock not in ("wall", "cpu"):
        from nowplan.errors import UsageError

        raise UsageError(f"PlannerConfig.clock is {config.clock!r}; use 'wall' or 'cpu'")
    return time.process_time if config.clock == "cpu" else time.perf_counter

