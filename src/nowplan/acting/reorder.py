"""RCHPN's plan rewrite (seed 002 Alg. 3 and 4) on the tail of one plan, for one belief.

:class:`Reorderer` holds the current belief and the plan's levels:

* ``select_gap`` (Alg. 3) starts at the first step and moves later steps in front of it while
  :func:`~nowplan.acting.arrange.arrange` prefers them first;
* ``select_parallel_ops`` (Alg. 4) pulls later steps next to the first while ``arrange`` says to
  combine them, up to the complexity limit, and :func:`combine_goals` makes their joint subgoal;
* every move is kept only if the reordered plan is still valid (:meth:`Reorderer.valid`): its
  pre-images, recomputed by regression from the plan's goal, chain back to a ``g0`` the belief
  satisfies.

The executive's side (which step to take, the combined step's level map, the budgets below a
combined step) is :class:`nowplan.acting.peephole.Peephole`.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from nowplan.acting.arrange import Arrange, Subgoal, arrange, depends, nothing_goes_first
from nowplan.acting.resources import Estimator, ResourceModel, resource_model
from nowplan.acting.truth import HoldsFn
from nowplan.core.atoms import Atom, Goal
from nowplan.core.domain import Domain
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Action
from nowplan.planning.plan import Plan
from nowplan.planning.regression import PlannerConfig, preimage, static_drop

# a cached pre-image's key: ids of the goal and the operator, the operator's level, the static
# predicates left out (``Reorderer.drop``)
PreimageKey = tuple[int, int, "int | None", frozenset[str]]


def estimate_config(planner: PlannerConfig | None, nodes: int = 300) -> PlannerConfig:
    """The estimator's small searches: ``planner``'s heuristic and engine, ``nodes`` expansions."""
    return replace(planner or PlannerConfig(), max_nodes=nodes, shortcut_nodes=nodes, time_limit=30.0,
                   serialization=True, monotonic=False, weight=1.0, improve=0.0)


@dataclass(frozen=True)
class PeepholeConfig:
    max_combined: int = 4  # complexity limit: operators in one combined subgoal
    # a step with fewer criticality classes still hidden is only reordered, never combined:
    # its refinement is its last one, so there is no abstract structure left to share
    min_hidden_to_combine: int = 2
    joint_search: bool = True  # plan combined subgoals without the random-serialization shortcut
    joint_weight: float = 1.0  # A* weight for those joint plans
    max_moves: int = 0  # moves per SelectGap call (0: the square of the plan length)
    # the small searches of the resource and effort estimates, bounded by nodes (a wall-clock
    # bound would make runs depend on the machine).  None: the executive's planner settings (its
    # heuristic, so the estimates are cost-aware where the domain's planner is, e.g. marsupial's
    # LM-cut) with ``estimate_nodes``; on marsupial that made the same decisions at 1.2-2x the
    # estimator's CPU (docs/peephole.md), so the default stays the engine's default heuristic
    estimate_search: PlannerConfig | None = field(default_factory=lambda: estimate_config(None))
    estimate_nodes: int = 300
    # node budget of every search below a combined step (its joint subgoal and their refinements:
    # the call's shortcuts and full search together, PlannerConfig.call_nodes); 0: the planner's
    # own budgets.  A combination whose refinement needs more is given up in this belief, as HPN
    # would not have made it
    joint_nodes: int = 500
    # searches below a combined step regress facts that hold through zero-cost operators into other
    # facts that hold (PlannerConfig.held_rewrites).  Off: a joint plan that would undo such a fact
    # and make it true again is not looked for (the steps are then refined one at a time, as HPN
    # does), and A* no longer meets every subset of the held facts rewritten (on marsupial, each
    # held same_city of a package the subgoal does not move doubled a joint search's nodes)
    held_rewrites: bool = False
    # after SelectParallelOps, move the prerequisites of a step that would join the group in front
    # of it (:mod:`nowplan.acting.gather`; ours, not in the paper)
    gather: bool = True
    # node budget of the refinement of a step taken alone that was part of a combination whose
    # joint planning failed earlier in the run (0: the planner's own budgets).  On marsupial these
    # are unloads of a package buried in a bay that combined loads filled: refined alone at the
    # loader's level, the full search proved them unsolvable after 3-19 k expansions each (0.3-2.1
    # CPU s, most of RCHPN's extra time on the problems where it gains nothing) and the executive
    # then backtracked, as it does after the budget
    fallout_nodes: int = 500


class Reorderer:
    """Alg. 3 and 4 on the tail of one plan, for one belief."""

    def __init__(
        self,
        domain: Domain,
        objects: Any,
        belief: Any,
        levels: LevelMap,
        model: ResourceModel | None = None,
        config: PeepholeConfig | None = None,
        failed: Sequence[frozenset[Any]] = (),
        planner: PlannerConfig | None = None,
        regressed: dict[PreimageKey, tuple[Goal, Action, Goal | None]] | None = None,
        holds: HoldsFn | None = None,
    ) -> None:
        self.domain = domain
        # truth in the belief (``holds``: the caller's, e.g. a TruthMemo's for this belief, which the
        # rewrite's tests share with the highest true kernel's)
        self._holds_given = holds is not None
        self.holds: HoldsFn = holds if holds is not None else (lambda a: domain.holds(a, belief))
        self.failed = failed  # combinations (sets of action keys) found unplannable in this belief
        self.belief = belief
        self.levels = levels
        self.model = model or resource_model(domain)
        self.config = config or PeepholeConfig()
        self._drop: frozenset[str] | None = None  # static predicates left out of pre-images (``drop``)
        search = self.config.estimate_search or estimate_config(planner, self.config.estimate_nodes)
        self.estimator = Estimator(domain, objects, belief, self.model, search, holds=holds)
        self.moves: list[str] = []
        self.validity_checks = 0
        # pre-images already computed, by (id of the goal, id of the operator, its level): the
        # candidate orders share their tails, so re-validating one regresses only its new head.  A
        # pre-image does not depend on the belief (only on the goal, the operator, its level and
        # :attr:`drop`), so the caller may pass one table for every Reorderer of a run
        # (``Peephole``: the plan's pre-images after a rewrite are these goal objects, and the next
        # step's candidates regress through the same tails again).  The goal and operator are kept
        # in the value, so the ids are never reused while cached
        self._regressed = {} if regressed is None else regressed
        self.regressions = 0  # pre-images computed (not found in the cache)
        # per action key, for this level map (SelectGap, SelectParallelOps and Gather ask again and again)
        self._arrangeable: dict[Any, bool] = {}
        self._combinable: dict[Any, bool] = {}

    @property
    def drop(self) -> frozenset[str]:
        """The static predicates left out of pre-images, found when a pre-image is first needed
        (most rewrites validate nothing)."""
        if self._drop is None:
            self._drop = static_drop(self.domain, self.belief)
        return self._drop

    # -- validity ---------------------------------------------------------------
    def chain(self, ops: Sequence[Action], goal: Goal) -> tuple[list[Action], list[Goal]] | None:
        """Regress ``goal`` back through ``ops``: the kept operators and ``[g0, …, gm = goal]``.

        A step that achieves nothing the rest of the plan needs and whose
        regression fails (a now-redundant step after a move, e.g. an
        inference already made true) is dropped; any other failure is None.
        """
        rules = self.domain.rules
        kept: list[Action] = []
        goals = [goal]
        g = goal
        for a in reversed(ops):
            pre = self._preimage(g, a)
            if pre is None:
                table = g.by_key()
                useful = any(
                    (w := table.get(e.key)) is not None and rules.rule(w.predicate).entails(e.value, w.value)
                    for e in a.effects()
                )
                if useful:
                    return None
                continue
            kept.append(a)
            g = pre
            goals.append(g)
        kept.reverse()
        goals.reverse()
        return kept, goals

    def _preimage(self, g: Goal, a: Action) -> Goal | None:
        """``preimage(g, a)`` at ``a``'s level, computed once per goal object and operator."""
        level = self.levels.level(a)
        key = (id(g), id(a), level, self.drop)
        hit = self._regressed.get(key)
        if hit is not None and hit[0] is g and hit[1] is a:
            return hit[2]
        self.regressions += 1
        pre = preimage(g, a, level, self.domain, self.drop)
        self._regressed[key] = (g, a, pre)
        return pre

    def can_follow(self, a: Action, before: Sequence[Action]) -> bool:
        """A necessary condition, found without regressing, for keeping ``a`` right after ``before``
        (the steps ahead of it in a reordered tail) in a plan :meth:`valid` accepts: each of ``a``'s
        preconditions at its level that no effect of ``before`` touches holds now.

        The regression adds ``a``'s preconditions (those of :attr:`drop` excepted) to the pre-image
        before ``a`` (merged with an atom of the same fluent, the merge entails them); an atom no
        operator of ``before`` has an effect on stays as it is down to ``g0``, which the belief
        must satisfy.  (A plan in which ``a`` is dropped as redundant does not keep ``a`` there.)
        On marsupial, most candidate combinations of top-level steps that failed validity failed
        only there: an Unload pulled ahead of the steps that bring its package to the vehicle.
        """
        touched = {e.key for b in before for e in b.effects()}
        drop, holds = self.drop, self.holds
        for p in a.preconditions(self.levels.level(a)):
            if p.predicate in drop or p.key in touched:
                continue
            if not holds(p):
                return False
        return True

    def valid(self, ops: Sequence[Action], goal: Goal) -> tuple[list[Action], list[Goal]] | None:
        """The plan (redundant steps dropped) and its pre-images if it is valid from the belief."""
        self.validity_checks += 1
        res = self.chain(ops, goal)
        if res is None:
            return None
        g0 = res[1][0]
        if not (all(map(self.holds, g0.atoms)) if self._holds_given else self.domain.satisfies(self.belief, g0)):
            return None
        return res

    # -- the preference ---------------------------------------------------------
    def arrangeable(self, a: Action) -> bool:
        known = self._arrangeable.get(a.key)
        if known is None:
            names = self.model.arrangeable
            known = self._arrangeable[a.key] = not self.levels.is_primitive(a) and (names is None or a.name in names)
        return known

    def combinable(self, a: Action) -> bool:
        known = self._combinable.get(a.key)
        if known is None:
            known = self._combinable[a.key] = (
                self.arrangeable(a) and self.levels.describe(a) >= self.config.min_hidden_to_combine)
        return known

    def arrange(self, s1: Subgoal, s2: Subgoal, want: Arrange | None = None) -> Arrange:
        """``arrange`` with the combination rule of ours; ``want``: see :func:`~.arrange.arrange`."""
        verdict = arrange(
            s1, s2, self.belief, domain=self.domain, levels=self.levels, estimator=self.estimator,
            model=self.model, want=want,
        )
        if verdict is Arrange.COMBINE and not all(self.combinable(a) for a in (*s1.actions, *s2.actions)):
            # nothing left to share at this level: independent, so the easier one first
            e1 = sum(self.estimator.effort(a, self.levels) for a in s1.actions)
            e2 = sum(self.estimator.effort(a, self.levels) for a in s2.actions)
            return Arrange.SECOND if e2 < e1 else Arrange.FIRST
        return verdict

    # -- Alg. 3 -------------------------------------------------------------------
    def select_gap(self, ops: list[Action], goals: list[Goal]) -> tuple[list[Action], list[Goal]]:
        """Move later steps before the first while ``arrange`` prefers them (``goals`` = chain)."""
        limit = self.config.max_moves or max(len(ops) ** 2, 1)
        moves = 0
        while ops and self.arrangeable(ops[0]) and moves < limit:
            first = Subgoal((ops[0],), goals[1])
            moved = False
            settled = False  # whether nothing_goes_first was asked for ``first``
            for j in range(1, len(ops)):
                if not self.arrangeable(ops[j]) or not self.can_follow(ops[j], ()):
                    continue
                if not settled and not self._depends_either(first, ops[j]):
                    # the first candidate ``arrange`` would estimate ``first`` for: when ``first``
                    # has nothing to wait for, no later step is preferred before it
                    settled = True
                    if nothing_goes_first(first, self.estimator, self.levels, self.model):
                        break
                if self.arrange(first, Subgoal((ops[j],), goals[j + 1]), Arrange.SECOND) is not Arrange.SECOND:
                    continue
                new = [ops[j], *ops[:j], *ops[j + 1 :]]
                res = self.valid(new, goals[-1])
                if res is not None and res[0][:1] == new[:1]:
                    self.moves.append(f"moved {ops[j]} before {ops[0]}")
                    self.note_dropped(new, res[0])
                    ops, goals = res
                    moved = True
                    moves += 1
                    break
            if not moved:
                break
        return ops, goals

    def _depends_either(self, s1: Subgoal, a: Action) -> bool:
        """``arrange``'s first test (FIRST whatever the estimates): either needs an effect of the other."""
        return depends(self.domain, s1.actions, (a,), self.levels) or depends(self.domain, (a,), s1.actions, self.levels)

    def note_dropped(self, before: Sequence[Action], after: Sequence[Action]) -> None:
        """Log, in :attr:`moves`, each step of ``before`` that a re-validation left out of ``after``."""
        rest = list(after)
        for a in before:
            if a in rest:
                rest.remove(a)
            else:
                self.moves.append(f"dropped {a} (no longer needed)")

    def failed_within(self, ops: Sequence[Action]) -> bool:
        """Whether these operators include a combination whose joint planning failed."""
        keys = {a.key for a in ops}
        return any(f <= keys for f in self.failed)

    # -- Alg. 4 -------------------------------------------------------------------
    def select_parallel_ops(
        self, ops: list[Action], goals: list[Goal]
    ) -> tuple[list[Action], list[Goal], int]:
        """Pull steps to combine next to the first; returns the plan and the last combined index."""
        last = 0
        if not ops or not self.combinable(ops[0]):
            return ops, goals, last
        j = 1
        while j < len(ops) and last + 1 < self.config.max_combined:
            if (self.combinable(ops[j]) and not self.failed_within([*ops[: last + 1], ops[j]])
                    and self.can_follow(ops[j], ops[: last + 1])):
                group = Subgoal(tuple(ops[: last + 1]), goals[last + 1])
                if self.arrange(group, Subgoal((ops[j],), goals[j + 1]), Arrange.COMBINE) is Arrange.COMBINE:
                    new = [*ops[: last + 1], ops[j], *ops[last + 1 : j], *ops[j + 1 :]]
                    res = self.valid(new, goals[-1])
                    if res is not None and res[0][: last + 2] == new[: last + 2]:
                        self.moves.append(f"combined {ops[j]} with {group}")
                        self.note_dropped(new, res[0])
                        j -= sum(1 for i in _dropped_positions(new, res[0]) if i <= j)
                        ops, goals = res
                        last += 1
            j += 1
        return ops, goals, last


def combine_goals(ops: Sequence[Action], goals: Sequence[Goal], last: int) -> Subgoal:
    """CombineGoals: the operators ``ops[0..last]`` with the pre-image after the last of them.

    In a valid plan that pre-image holds exactly what the rest of the plan
    needs from the combined operators, so planning for it achieves them jointly.
    """
    return Subgoal(tuple(ops[: last + 1]), goals[last + 1])


def highest_applicable(
    domain: Domain, belief: Any, plan: Plan, watch: dict[int, Atom] | None = None, holds: HoldsFn | None = None
) -> int | None:
    """The highest ``i`` with the belief in ``g_i`` (``n`` if the goal already holds).

    ``watch`` (kept by the caller for this plan across beliefs) holds, per pre-image found false,
    the atom that was false: it is tested first next time, so a pre-image that stays false (most
    of a long plan's, while its first steps are taken) costs one test instead of a pass over its
    atoms up to a false one.  The answer is the same with or without it.  ``holds`` answers
    ``domain.holds(atom, belief)`` (e.g. a :class:`~nowplan.acting.truth.TruthMemo`'s, shared by
    the calls made in one belief: the pre-images of a plan, and of the plans pushed in that
    belief, repeat most atoms).
    """
    if holds is None:
        holds = lambda a: domain.holds(a, belief)  # noqa: E731
    for i in range(len(plan.steps) - 1, -1, -1):
        if watch is not None:
            w = watch.get(i)
            if w is not None and not holds(w):
                continue
        false = next((a for a in plan.steps[i].goal.atoms if not holds(a)), None)
        if false is None:
            return i
        if watch is not None:
            watch[i] = false
    return None


def _dropped_positions(before: Sequence[Action], after: Sequence[Action]) -> list[int]:
    """Positions of ``before`` missing from its subsequence ``after``."""
    out, k = [], 0
    for i, a in enumerate(before):
        if k < len(after) and after[k] == a:
            k += 1
        else:
            out.append(i)
    return out
