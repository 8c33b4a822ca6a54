"""What the goal-directed grounder looks up rather than computes per call.

:func:`unify_effect` unifies an effect template with a target atom;
``_effects_by_predicate`` indexes a domain's operators by the predicates
they change (kept per domain); ``_shared`` holds the answers the calls of
one problem share (kept per objects and static facts: the executive plans
many times with the same static facts: achievers, fills, each operator's
``_FillPlan`` and the static facts indexed by bound positions).
:class:`nowplan.planning.grounding.Grounder` uses all three.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Hashable, Iterator
from typing import Any

from nowplan.core.atoms import Atom, Var
from nowplan.core.domain import Domain
from nowplan.core.operators import Action, Operator
from nowplan.planning.generators_run import Misses


def unify_effect(effect: Atom, target: Atom, domain: Domain) -> dict[Var, Any] | None:
    """Bindings that make ``effect`` entail ``target``, or ``None``."""
    if effect.predicate != target.predicate or len(effect.args) != len(target.args):
        return None
    b: dict[Var, Any] = {}
    for e, t in zip(effect.args, target.args, strict=True):
        if isinstance(e, Var):
            if e in b and b[e] != t:
                return None
            b[e] = t
        elif e != t:
            return None
    ev = effect.value
    if isinstance(ev, Var):
        if ev in b and not domain.rules.rule(target.predicate).entails(b[ev], target.value):
            return None
        b.setdefault(ev, target.value)
    elif not domain.rules.rule(target.predicate).entails(ev, target.value):
        return None
    return b


_ByPred = dict[str, list[tuple[int, Operator, tuple[Atom, ...]]]]


def _effects_by_predicate(
    domain: Domain,
) -> tuple[_ByPred, dict[str, tuple[tuple[int, Operator, tuple[Atom, ...]], ...]], frozenset[str]]:
    """Per predicate the operators (in order) with an effect of it, and those effects; the same for
    operators with generators; the predicates such an operator achieves (kept per domain)."""
    hit = domain.facts.derived.get("effects by predicate")
    if hit is not None and hit[0] is domain.operators:
        return hit[1]  # type: ignore[no-any-return]
    out: _ByPred = {}
    for i, op in enumerate(domain.operators):
        per: dict[str, list[Atom]] = {}
        for e in op.effects:
            per.setdefault(e.predicate, []).append(e)
        for pred, effs in per.items():
            out.setdefault(pred, []).append((i, op, tuple(effs)))
    gen = {pred: tuple(e for e in entries if e[1].generators) for pred, entries in out.items()}
    answer = (out, gen, frozenset(p for p, e in gen.items() if e))
    domain.facts.derived["effects by predicate"] = (domain.operators, answer)
    return answer


class _Shared:
    """Grounding answers that depend only on a problem's objects and static facts."""

    def __init__(self) -> None:
        self.op_cache: dict[tuple[int, Atom], list[Action]] = {}
        self.fills: dict[tuple[int, frozenset[tuple[Var, type, Any]]], list[Action]] = {}  # instances per binding
        self.answers: dict[Atom, list[Action]] = {}  # achievers of atoms no generator achieves
        self.no_gen: dict[Atom, bool] = {}  # is an atom achieved by no operator with generators?
        self.fill_plans: dict[int, _FillPlan] = {}  # Grounder._fill_plan's answers (by operator identity, checked)
        self.fact_index: dict[tuple[str, int, tuple[int, ...]], dict[tuple[Any, ...], list[Any]]] = {}  # static facts


_SHARED_PER_DOMAIN = 4


class _PerState:
    """Answers that depend on one belief state too (with the objects, static facts and context).

    Kept for the few latest states, so that the calls made between two actions
    (the executive refines a step level by level from the same belief) ground
    each achiever, run each generator and test each atom once.
    """

    def __init__(self, state: Any) -> None:
        self.state = state  # held: the key is its id
        self.achievers: dict[Atom, list[Action]] = {}  # Grounder._cache
        self.by_reading: dict[tuple[Atom, Hashable], list[Action]] = {}  # Grounder._gen_cache
        self.holds: dict[Atom, bool] = {}  # the domain's tests on this state
        self.fholds: dict[int, bool] = {}  # the same by fact id
        self.held: set[int] = set()  # the fact ids found true
        self.costs: dict[tuple[str, tuple[Any, ...]], float] = {}  # belief-dependent action costs
        self.misses = Misses()  # generators whose proposals were all skipped (Grounder.misses)


_STATES_PER_DOMAIN = 4


def point_state(belief: Any) -> Any:
    """The immutable state of a plain point belief (a ``State``, or a ``SymbolicBelief`` itself), else ``None``.

    Only these are known to answer every question from that state alone: a
    subclass may keep more (a random generator, a belief of its own).
    """
    from nowplan.belief.symbolic import SymbolicBelief
    from nowplan.core.state import State

    if type(belief) is State:
        return belief
    if type(belief) is SymbolicBelief and type(belief.state) is State:
        return belief.state
    return None


def context_key(context: Any) -> Hashable | None:
    """What generators may read of ``context``, as a key; ``None`` where it cannot be one.

    Only an empty plan stack with extras of plain immutable values (numbers,
    strings, and tuples or frozensets of them) makes a key: a plan stack, or
    an object whose state could change between calls, does not.
    """
    if context is None:
        return ("none",)
    if context.plan_stack or not all(_plain(v) for v in context.extras.values()):
        return None
    return ("extras", tuple(sorted(context.extras.items())))


def _plain(v: Any, depth: int = 0) -> bool:
    """Is ``v`` an immutable value of builtin types (nested at most a few levels)?"""
    if v is None or type(v) in (bool, int, float, str, bytes):
        return True
    if type(v) in (tuple, frozenset) and depth < 4:
        return all(_plain(x, depth + 1) for x in v)
    return False


def _per_state(domain: Domain, key: Hashable, state: Any) -> _PerState:
    """The answers kept for ``state`` under ``key`` (the few latest keys per domain)."""
    store: dict[Hashable, _PerState] = domain.facts.derived.setdefault("per-state grounding", {})
    hit = store.get(key)
    if hit is None or hit.state is not state:
        if len(store) >= _STATES_PER_DOMAIN:
            store.pop(next(iter(store)))
        hit = store[key] = _PerState(state)
    else:  # latest last
        store[key] = store.pop(key)
    return hit


class _PerAtom:
    """Grounding answers per atom that depend only on a domain's operators (and its value rules)."""

    def __init__(self) -> None:
        self.unified: dict[tuple[int, Atom], list[dict[Var, Any]]] = {}  # bindings unifying effects
        self.goal_free: dict[Atom, bool] = {}  # do no achievers' generators read the goal?
        self.read_plans: dict[Atom, Any] = {}  # what to ask the generators' ``reads`` of a goal


def _per_atom(domain: Domain) -> _PerAtom:
    """The domain's :class:`_PerAtom` (made anew if its operators were replaced)."""
    hit = domain.facts.derived.get("per-atom grounding")
    if hit is not None and hit[0] is domain.operators:
        return hit[1]  # type: ignore[no-any-return]
    store = _PerAtom()
    domain.facts.derived["per-atom grounding"] = (domain.operators, store)
    return store


def _shared(domain: Domain, signature: Hashable) -> _Shared:
    store: dict[Hashable, _Shared] = domain.facts.grounding
    hit = store.get(signature)
    if hit is None:
        if len(store) >= _SHARED_PER_DOMAIN:
            store.pop(next(iter(store)))
        hit = store[signature] = _Shared()
    return hit


class _FillPlan:
    """An operator's static preconditions and typed parameters, as :meth:`Grounder._fill` uses them."""

    __slots__ = ("op", "statics", "later", "allobj", "typed")

    def __init__(
        self, op: Operator, statics: tuple[Atom, ...], later: tuple[Atom, ...], allobj: frozenset[str],
        typed: tuple[tuple[Var, frozenset[str]], ...],
    ) -> None:
        self.op = op
        self.statics = statics
        self.later = later
        self.allobj = allobj
        self.typed = typed


def _is_plain(domain: Domain, a: Atom) -> bool:
    """A static fluent that a belief can list facts of (no test function, boolean)."""
    pred = domain.predicates.get(a.predicate)
    return pred is not None and pred.test is None and a.value in (True, False)


_UNSET = object()


def completed(
    op: Operator,
    joined: Iterator[dict[Var, Any]],
    allobj: frozenset[str],
    typed: tuple[tuple[Var, frozenset[str]], ...],
    later: tuple[Atom, ...],
    check: Callable[[dict[Var, Any]], bool],
    objects_of: Callable[[str | None], list[str]],
) -> Iterator[dict[Var, Any]]:
    """The bindings of ``joined`` (the grounder's static join) type-checked against ``typed`` and
    completed with the objects of each free parameter's type, those failing ``check`` (the statics the
    join left for later) dropped (``Grounder._fill``)."""
    for jb in joined:
        # a value bound before the product that names an object of another type: not an instance
        bad = False
        for v, ok_objs in typed:
            val = jb.get(v, _UNSET)
            if val is not _UNSET and isinstance(val, str) and val in allobj and val not in ok_objs:
                bad = True
                break
        if bad:
            continue
        free = [v for v in op.params if v not in jb]
        if not free:
            if not later or check(jb):
                yield dict(jb)
            continue
        domains = [objects_of(op.type_of(v)) for v in free]
        for combo in itertools.product(*domains):
            full = dict(jb)
            full.update(zip(free, combo, strict=True))
            if later and not check(full):
                continue
            yield full
