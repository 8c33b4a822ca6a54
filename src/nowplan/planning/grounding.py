"""Goal-directed grounding: the operator instances that can achieve an atom.

An effect template is unified with the goal atom; the parameters left
unbound are filled, in this order, by the operator's generators (which see
the goal, the belief and the planning context), by joining static
preconditions against the facts the belief lists, and last by enumerating
typed objects.  Static preconditions (of predicates no operator changes) are
checked here once, so they never enter a pre-image (static fluents with a
test function are ordinary preconditions: they stay in pre-images when kept
at the plan's level).

Effect unification (``unify_effect``, re-exported here) and the grounder's
per-domain and per-problem stores are in :mod:`nowplan.planning.grounding_index`.
"""

from __future__ import annotations

from collections.abc import Callable, Hashable, Iterable, Iterator, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from nowplan.core.atoms import Atom, Goal, Var
from nowplan.belief.protocols import ListsFacts, offers
from nowplan.core.domain import Domain
from nowplan.core.operators import Action, Operator, ReadsFn, reads_nothing
from nowplan.planning.context import PlanningContext
from nowplan.planning.generators_run import Misses, run_generators
from nowplan.planning.grounding_index import (
    _effects_by_predicate, _FillPlan, _is_plain, _per_atom, _per_state, _PerAtom, _PerState, _shared, completed,
    context_key, point_state, unify_effect,
)
from nowplan.planning.task_answers import TaskAnswers

if TYPE_CHECKING:
    from nowplan.planning.ground_task import GroundTask

__all__ = ["Grounder", "unify_effect"]


class Grounder(TaskAnswers):
    """Caches achievers per atom for one planning problem (domain, objects, belief).

    With ``memo`` (the default) it also remembers, for the whole problem, the
    achievers of each generator-free operator per atom and the instances that
    complete each (operator, partial binding) by static joins and typed
    objects: both depend only on the static facts, so the answers and their
    order are the same as without (``memo = False`` recomputes them, for
    tests).  Per domain it keeps what depends on the operators alone, and per
    plain belief state the achievers, tests and costs (``per_state``).
    """

    memo = True

    def __init__(
        self,
        domain: Domain,
        objects: Mapping[str, str | None],
        belief: Any,
        context: PlanningContext | None = None,
        max_generator_values: int = 8,
        lists_facts: bool | None = None,
        signature: Hashable = None,
    ) -> None:
        """``signature``: :attr:`signature` as computed for an earlier belief whose static facts
        (and objects) are known to be these too; ``None``: computed here (it reads every static fact)."""
        self.domain = domain
        self.objects = dict(objects)
        self.belief = belief
        self.context = context
        self.max_generator_values = max_generator_values
        self._cache: dict[Atom, list[Action]] = {}
        self._static_cache: dict[Atom, bool] = {}
        self._by_type: dict[str | None, list[str]] = {}
        # does the belief list its facts (``lists_facts``: the caller has asked already)?
        self._facts_ok = offers(belief, ListsFacts) if lists_facts is None else lists_facts
        self._fill_plans: dict[int, _FillPlan] = {}
        self._fact_index: dict[tuple[str, int, tuple[int, ...]], dict[tuple[Any, ...], list[Any]]] = {}
        self._task: GroundTask | None = None
        self._allobj: frozenset[Any] | None = None
        self._op_cache: dict[tuple[int, Atom], list[Action]] = {}
        self._valued: dict[tuple[int, str, Any], int] = {}  # (operator, predicate, value): its effects that may give it
        self._fills: dict[tuple[int, frozenset[tuple[Var, type, Any]]], list[Action]] = {}
        self.signature: Hashable = None  # the objects and static facts (with a belief that lists facts)
        self._shared_answers: dict[Atom, list[Action]] | None = None  # generator-free achievers, per problem
        self._no_gen: dict[Atom, bool] = {}  # atoms no operator with generators achieves (see _no_generator)
        if self._facts_ok:
            self.signature = signature if signature is not None else self._signature()
        if self.memo and self._facts_ok:
            # both depend only on the objects and the static facts: share them between the calls
            # of one problem (the executive plans many times with the same static facts)
            shared = _shared(domain, self.signature)
            self._op_cache, self._fills = shared.op_cache, shared.fills
            self._shared_answers = shared.answers
            self._no_gen = shared.no_gen
            self._fill_plans = shared.fill_plans
            self._fact_index = shared.fact_index
        # per predicate: the operators (in order) with an effect of it, and those effects
        self._by_pred, self._gen_by_pred, self._gen_by_pred_nonempty = _effects_by_predicate(domain)
        self._gen_cache: dict[tuple[Atom, Hashable], list[Action]] = {}
        # per atom, what depends on the operators only (kept per domain with ``memo``: each call of a
        # problem asks the same atoms again, and more of them the more objects there are)
        per_atom = _per_atom(domain) if self.memo else _PerAtom()
        self._unify_cache = per_atom.unified
        self._goal_free = per_atom.goal_free
        self._read_plans = per_atom.read_plans
        # with a plain point belief, what depends on its state too is kept per state: the calls made
        # between two actions (a step refined level by level) share their achievers and tests
        self.per_state: _PerState | None = None
        state = point_state(belief) if self.memo and self._facts_ok else None
        ckey = context_key(context) if state is not None else None
        if state is not None and ckey is not None:
            self.per_state = _per_state(domain, (id(state), self.signature, ckey, max_generator_values), state)
            self._cache = self.per_state.achievers
            self._gen_cache = self.per_state.by_reading
            self._static_cache = self.per_state.holds  # (the domain's test, as the search's holds)
        # generators whose proposals were all skipped (kept with the state's answers, which reuse them)
        self.misses = self.per_state.misses if self.per_state is not None else Misses()
        self._last_reading: tuple[Atom, Goal, tuple[Hashable, ...]] | None = None  # (a goal is immutable)
        self.kept = False  # was the last answer of achievers() kept (the same list object next time)?
        # ground actions of the domain, one object per instance (planners keep data on them)
        self._actions: dict[tuple[int, tuple[Any, ...]], Action] = domain.facts.actions

    def _signature(self) -> Hashable:
        """The objects and the facts of the static predicates that ``_fill`` joins and checks."""
        preds = sorted(n for n in self.domain.static_predicates if self.domain.predicates[n].test is None)
        facts = tuple((n, frozenset(map(tuple, self.belief.facts(n)))) for n in preds)
        return (frozenset(self.objects.items()), facts)

    @property
    def lists_facts(self) -> bool:
        """Does the belief list its facts (``facts``/``atoms``)?"""
        return self._facts_ok

    # -- helpers -------------------------------------------------------------
    def objects_of(self, t: str | None) -> list[str]:
        if t not in self._by_type:
            allobj = {**dict(self.domain.constants), **self.objects}
            ok = self.domain.subtypes(t) if t is not None else None
            self._by_type[t] = sorted(o for o, ot in allobj.items() if ok is None or ot in ok)
        return self._by_type[t]

    def is_static(self, a: Atom) -> bool:
        return a.predicate in self.domain.static_predicates

    def static_holds(self, a: Atom) -> bool:
        r = self._static_cache.get(a)
        if r is None:
            r = self.domain.holds(a, self.belief)
            self._static_cache[a] = r
        return r

    # -- achievers -----------------------------------------------------------
    def achievers(self, target: Atom, goal: Goal | Callable[[], Goal]) -> list[Action]:
        """Ground actions one of whose effects entails ``target``.

        ``goal`` (the subgoal being regressed, for generators) may be given as a
        function that makes it, called only when a generator has to run.
        Achievers that no generator takes part in are kept per atom; with
        ``memo``, those of operators whose generators all declare what they
        read of the goal (``Generator.reads``) are kept per atom and reading.
        """
        self.kept = True  # the answer is kept: the same list comes back for the same question
        cached = self._cache.get(target)
        if cached is not None:
            return cached
        if self._shared_answers is not None and self._no_generator(target):
            # no operator with generators achieves this atom: the answer depends on the static facts only
            cached = self._shared_answers.get(target)
            if cached is not None:
                self._cache[target] = cached
                return cached
        entries = self._by_pred.get(target.predicate, ())
        gen_entries = self._gen_by_pred.get(target.predicate, ())
        key: tuple[Atom, Hashable] | None = None
        free = self.goal_free(target)
        if gen_entries and self.memo and not free:
            g = goal() if callable(goal) else goal
            goal = g
            r = self._readings(gen_entries, target, g)
            if r is not None:
                key = (target, r)
                hit = self._gen_cache.get(key)
                if hit is not None:
                    return hit
        out: list[Action] = []
        seen: set[tuple[str, tuple[Any, ...]]] = set()
        groups: dict[int, list[int]] | None | bool = False  # the task's adders by operator (not asked yet)
        for i, op, effs in entries:
            if self.memo and not op.generators:
                acts = self._op_cache.get((i, target))
                if acts is None:
                    if groups is False:
                        groups = self._task_groups(target)
                    acts = None if not isinstance(groups, dict) else self._task_achievers(i, effs, target, groups)
                    if acts is None:
                        acts = list(self._op_achievers(i, op, effs, target, goal))
                    self._op_cache[(i, target)] = acts
                found: Iterable[Action] = acts
            else:
                found = self._op_achievers(i, op, effs, target, goal)
            for act in found:
                if act.key not in seen:
                    seen.add(act.key)
                    out.append(act)
        # generators see the goal: keep the answer per atom only when none that reads it takes part
        if not gen_entries or free and self.memo:
            self._cache[target] = out
            if self._shared_answers is not None and self._no_generator(target):
                self._shared_answers[target] = out
        elif key is not None:
            self._gen_cache[key] = out
        else:
            self.kept = False
        return out

    def known(self, target: Atom) -> list[Action] | None:
        """``target``'s achievers if :meth:`achievers` has them kept for this problem and state
        without running a generator (no grounding here), else ``None``."""
        cached = self._cache.get(target)
        if cached is None and self._shared_answers is not None and self._no_generator(target):
            cached = self._shared_answers.get(target)
        return cached

    @property
    def shares_answers(self) -> bool:
        """Are the generator-free achievers kept per problem (every call of it gets the same lists)?"""
        return self._shared_answers is not None

    def shares_answer(self, target: Atom) -> bool:
        """Is ``target``'s answer the one every call of this problem gets (no generator achieves it)?"""
        return self._shared_answers is not None and self._no_generator(target)

    def _no_generator(self, target: Atom) -> bool:
        """Can no effect of an operator with generators entail ``target`` (kept per problem)?

        Then its achievers depend on the objects and static facts only, even
        where operators with generators change its predicate (marsupial's Load
        clears ``at(p, l)``, so every ``at`` goal was grounded again per call).
        """
        if target.predicate not in self._gen_by_pred_nonempty:
            return True
        store = self._no_gen
        r = store.get(target)
        if r is None:
            r = store[target] = not any(
                unify_effect(e, target, self.domain) is not None
                for _, _, effs in self._gen_by_pred[target.predicate] for e in effs)
        return r

    def _readings(
        self, gen_entries: Sequence[tuple[int, Operator, tuple[Atom, ...]]], target: Atom, goal: Goal
    ) -> tuple[Hashable, ...] | None:
        """What the generators that achieve ``target`` read of ``goal``; ``None``: unknown."""
        last = self._last_reading  # (the relaxation asks for a fact's key, then for its achievers)
        if last is not None and last[0] is target and last[1] is goal:
            return last[2]
        plan = self._read_plans.get(target, _UNSET)
        if plan is _UNSET:
            plan = self._read_plans[target] = self._read_plan(gen_entries, target)
        if plan is None:
            return None
        r = tuple([reads(b, goal) for reads, b in plan])
        self._last_reading = (target, goal, r)
        return r

    def _read_plan(
        self, gen_entries: Sequence[tuple[int, Operator, tuple[Atom, ...]]], target: Atom
    ) -> tuple[tuple[ReadsFn, dict[Var, Any]], ...] | None:
        """The (reads, bindings) pairs to ask for ``target``'s readings, or ``None`` if one is unknown."""
        out: list[tuple[ReadsFn, dict[Var, Any]]] = []
        for i, op, effs in gen_entries:
            for b in self._unified(i, effs, target):
                for gen in op.generators:
                    if gen.reads is None or not all(v in b for v in gen.inputs):
                        return None
                    out.append((gen.reads, b))
        return tuple(out)

    def reading(self, target: Atom, goal: Goal) -> Hashable:
        """A key for what ``target``'s achievers depend on in ``goal``: equal keys, equal achievers."""
        r = self._readings(self._gen_by_pred.get(target.predicate, ()), target, goal)
        return ("goal", goal) if r is None else r

    def goal_free(self, target: Atom) -> bool:
        """Do ``target``'s achievers not depend on the goal (no generator that reads it takes part)?"""
        r = self._goal_free.get(target)
        if r is None:
            r = True
            for i, op, effs in self._gen_by_pred.get(target.predicate, ()):
                for b in self._unified(i, effs, target):
                    # a generator that reads the goal, or one whose inputs this effect leaves unbound: it
                    # yields nothing here by its contract (bindings.get), which is no proof that nothing
                    # achieves the atom (a held-out greenhouse's spray(r, p, q, c, c2): charge(c1) from
                    # its charge effect, the plant unbound; the lazy relaxation called the two sprays
                    # two plants needed a dead end and the planner "unsolvable")
                    if any(g.reads is not reads_nothing or any(v not in b for v in g.inputs)
                           for g in op.generators):
                        r = False
                        break
                if not r:
                    break
            self._goal_free[target] = r
        return r

    def _unified(self, i: int, effs: tuple[Atom, ...], target: Atom) -> list[dict[Var, Any]]:
        """The bindings that make each of operator ``i``'s ``effs`` entail ``target`` (kept: do not change them)."""
        key = (i, target)
        out = self._unify_cache.get(key)
        if out is None:
            out = self._unify_cache[key] = [
                b for b in (unify_effect(e, target, self.domain) for e in effs) if b is not None
            ]
        return out

    def _op_achievers(
        self, i: int, op: Operator, effs: tuple[Atom, ...], target: Atom, goal: Goal | Callable[[], Goal]
    ) -> Iterator[Action]:
        for b in self._unified(i, effs, target):
            yield from self._instances(i, op, dict(b), goal)

    def instantiate(self, i: int, op: Operator, full: Mapping[Var, Any]) -> Action:
        """``op.instantiate(full)``, one object per ground instance of the domain."""
        args = tuple(full[v] for v in op.params) if all(v in full for v in op.params) else None
        if args is None:
            return op.instantiate(full)  # raises: unbound parameters
        try:
            act = self._actions.get((i, args))
        except TypeError:  # an argument that cannot be hashed
            return op.instantiate(full)
        if act is None:
            act = self._actions[(i, args)] = op.instantiate(full)
        return act

    def _instances(
        self, i: int, op: Operator, b: dict[Var, Any], goal: Goal | Callable[[], Goal]
    ) -> Iterator[Action]:
        """The ground instances of operator ``i`` extending ``b`` (generators, static joins, typed objects)."""
        for gb in self._run_generators(op, b, goal):
            if not self.memo:
                for full in self._fill(op, gb):
                    yield self.instantiate(i, op, full)
                continue
            try:
                # with the value's type: 1, 1.0 and True are equal keys but not the same binding
                key = (i, frozenset((k, type(v), v) for k, v in gb.items()))
                acts = self._fills.get(key)
            except TypeError:  # a generator value that cannot be hashed: no memo for it
                for full in self._fill(op, gb):
                    yield self.instantiate(i, op, full)
                continue
            if acts is None:  # (the domain keeps one object per instance: the same ones as made anew)
                acts = self._fills[key] = [self.instantiate(i, op, full) for full in self._fill(op, gb)]
            yield from acts

    def _run_generators(
        self, op: Operator, b: dict[Var, Any], goal: Goal | Callable[[], Goal]
    ) -> Iterator[dict[Var, Any]]:
        """The bindings of ``op``'s generators extending ``b`` (:mod:`nowplan.planning.generators_run`)."""
        if not op.generators:
            return iter((b,))
        return run_generators(op, b, goal() if callable(goal) else goal, self.belief, self.context,
                              self.max_generator_values, self.misses)

    def _fill_plan(self, op: Operator) -> _FillPlan:
        """What :meth:`_fill` needs of ``op``, worked out once per operator."""
        plan = self._fill_plans.get(id(op))
        if plan is None or plan.op is not op:
            statics = tuple(
                p.atom for p in op.preconditions if self.is_static(p.atom) and _is_plain(self.domain, p.atom)
            )
            # statics the join does not check itself (negative ones, or every one without listed facts)
            # (and those of a predicate whose listed facts may carry values other than True)
            later = tuple(s for s in statics if not self._facts_ok or s.value is not True
                          or not self.domain.predicates[s.predicate].boolean)
            # per parameter: the objects of its type (a set) when a bound value must be type-checked
            allobj = frozenset(self.objects_of(None))
            typed: list[tuple[Var, frozenset[str]]] = []
            if op.param_types:
                outs = {v for g in op.generators for v in g.outputs}
                for v, t in zip(op.params, op.param_types, strict=True):
                    if t is not None and v not in outs:
                        typed.append((v, frozenset(self.objects_of(t))))
            plan = self._fill_plans[id(op)] = _FillPlan(op, statics, later, allobj, tuple(typed))
        return plan

    def _facts_by(self, pred: str, arity: int, positions: tuple[int, ...]) -> dict[tuple[Any, ...], list[Any]]:
        """The listed facts of the static ``pred`` with ``arity`` arguments by their values at ``positions``,
        in the belief's order (kept per problem: they depend on the static facts only)."""
        k = (pred, arity, positions)
        table = self._fact_index.get(k)
        if table is None:
            table = self._fact_index[k] = {}
            for args in self.belief.facts(pred):
                if len(args) == arity:
                    table.setdefault(tuple(args[i] for i in positions), []).append(args)
        return table

    def _fill(self, op: Operator, b: dict[Var, Any]) -> Iterator[dict[Var, Any]]:
        """Complete ``b`` by joining static preconditions with listed facts, then typed objects.

        Statics the join matched are not checked again; the values the join or ``b``
        bound are type-checked (those taken from typed objects are typed already).
        """
        plan = self._fill_plan(op)
        statics, later = plan.statics, plan.later
        for v, ok_objs in plan.typed:  # a value of ``b`` that names an object of another type: no instance
            val = b.get(v, _UNSET)  # (checked again after the join; here it spares the join)
            if val is not _UNSET and isinstance(val, str) and val in plan.allobj and val not in ok_objs:
                return

        def check(bind: dict[Var, Any]) -> bool:
            for s in later:
                g = s.bind(bind)
                if g.ground and not self.static_holds(g):
                    return False
            return True

        def join(i: int, cur: dict[Var, Any]) -> Iterator[dict[Var, Any]]:
            if i == len(statics):
                yield cur
                return
            s = statics[i]
            if all(not isinstance(a, Var) or a in cur for a in s.args):
                if self.static_holds(s.bind(cur)):
                    yield from join(i + 1, cur)
                return
            if not self._facts_ok or s.value is not True:
                yield from join(i + 1, cur)  # enumerate later
                return
            positions = tuple(k for k, a in enumerate(s.args) if not isinstance(a, Var) or a in cur)
            key = tuple(cur[a] if isinstance(a, Var) else a for a in (s.args[k] for k in positions))
            try:
                rows: Iterable[Any] = self._facts_by(s.predicate, len(s.args), positions).get(key, ())
            except TypeError:  # a bound value that cannot be hashed (a generator's): scan the facts
                rows = self.belief.facts(s.predicate)
            for args in rows:
                nxt = dict(cur)
                ok = True
                for t, v in zip(s.args, args, strict=False):
                    if isinstance(t, Var):
                        if t in nxt and nxt[t] != v:
                            ok = False
                            break
                        nxt[t] = v
                    elif t != v:
                        ok = False
                        break
                if ok and len(args) == len(s.args):
                    yield from join(i + 1, nxt)

        allobj, typed = plan.allobj, plan.typed
        try:
            yield from completed(op, join(0, b), allobj, typed, later, check, self.objects_of)
        finally:
            del join  # it refers to itself: a cycle only the collector would free


_UNSET = object()

