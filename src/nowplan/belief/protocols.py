"""What the engine asks of a belief: one required method and named optional capabilities.

Every belief implements :class:`~nowplan.worlds.base.Belief` (``update``).
What else it offers decides which parts of the engine can use it; each
capability is a :class:`typing.Protocol`, tested with ``isinstance`` in one
place, never by probing attribute names:

=====================  ================================================  ===========================================
capability             members                                           used by
=====================  ================================================  ===========================================
:class:`HasValues`     ``value(key)``: a fluent's value (``None``:       truth of atoms whose predicate has no test
                       unknown/absent)
:class:`ListsFacts`    ``facts(predicate)``, ``atoms()``                 static facts at grounding, h_add / h_FF,
                                                                         forward search, mutex inference, PDDL out
:class:`HasState`      ``state``: a point :class:`State`                 the expected-vs-observed monitor
:class:`HasUnknowns`   ``unknowns()``: fluents unknown either way        negative literals (they do not hold)
:class:`Reobserves`    ``reobserve()``: look again                       the monitor, when nothing can be planned
:class:`HasStreams`    ``streams``: a :class:`StreamSet`                 the online policy (sampling pools grow)
:class:`HasHeuristic`  ``planning_heuristic(goal, belief, holds)``       the online policy's planner
:class:`AfterAction`   ``after_action(trace, action, observation)``      the online policy (e.g. a demo's frames)
=====================  ================================================  ===========================================

:func:`check_belief` is called once when a run starts: a belief that lacks
``update``, or lacks ``value`` while some predicate has no test, is a
:class:`~nowplan.errors.ModelError` in one line.  Base classes for the
common cases: :class:`nowplan.belief.symbolic.SymbolicBelief` (an observed
symbolic state that lists its facts) and
:class:`nowplan.belief.particles.ParticleBelief` (weighted samples).
"""

from __future__ import annotations

import logging
from collections.abc import Callable, Iterable, Iterator
from typing import TYPE_CHECKING, Any, Protocol, runtime_checkable

from nowplan.core.atoms import Atom, Goal, Term
from nowplan.core.operators import Action
from nowplan.errors import ModelError
from nowplan.worlds.base import Belief, Observation

if TYPE_CHECKING:
    from nowplan.core.domain import Domain
    from nowplan.core.state import State
    from nowplan.planning.streams import StreamSet
    from nowplan.trace import Trace

log = logging.getLogger(__name__)

Key = tuple[str, tuple[Term, ...]]


@runtime_checkable
class HasValues(Protocol):
    """``value(key)``: the value of fluent ``(predicate, args)``; ``None`` or ``False`` when it does not hold."""

    def value(self, key: Key) -> Any: ...


@runtime_checkable
class ListsFacts(Protocol):
    """The belief lists its true facts (a closed world): grounding, relaxed heuristics, forward search."""

    def facts(self, predicate: str) -> Iterable[tuple[Term, ...]]: ...

    def atoms(self) -> Iterator[Atom]: ...


@runtime_checkable
class HasUnknowns(Protocol):
    """``unknowns()``: the fluents the belief is sure of neither way (a particle belief's odds between
    ``1 - threshold`` and ``threshold``).  Neither such a fluent nor its negation holds: without it, a
    negative literal on a fluent the belief lists as absent holds (closed world)."""

    def unknowns(self) -> frozenset[Key]: ...


@runtime_checkable
class HasState(Protocol):
    """A point belief: ``state`` is the one :class:`State` it takes to be true (the monitor compares it)."""

    @property
    def state(self) -> State: ...


@runtime_checkable
class Reobserves(Protocol):
    """``reobserve()`` takes a fresh look at the world (the monitor asks when no repair can be planned)."""

    def reobserve(self) -> None: ...


@runtime_checkable
class HasStreams(Protocol):
    """``streams``: the :class:`StreamSet` whose sampling pools the online policy grows on failure."""

    @property
    def streams(self) -> StreamSet | None: ...


DomainHeuristic = Callable[[Goal, Any, Callable[[Atom], bool]], float]


@runtime_checkable
class HasHeuristic(Protocol):
    """``planning_heuristic(goal, belief, holds) -> cost``: a domain's goal-distance estimate."""

    @property
    def planning_heuristic(self) -> DomainHeuristic | None: ...


@runtime_checkable
class GivesUp(Protocol):
    """A belief whose generators guard against planning loops (e.g. NAMO's move generator).

    ``planning_gave_up(context)``: why the search of the planning call with ``context`` should end
    (its generators gave up on it), or None; the regression search polls it as it expands nodes.
    A planning call for the whole problem is then made in two passes (:mod:`nowplan.acting.whole`).
    """

    def planning_gave_up(self, context: Any) -> str | None: ...


@runtime_checkable
class ReportsGiveUp(Protocol):
    """A :class:`GivesUp` belief that also says, after a planning call, whether its generators gave up
    on it (``generators_gave_up(context)``: why, or None), also where the search went on without them
    (a whole-problem call's restricted pass): such a search's exhausted space proves nothing."""

    def generators_gave_up(self, context: Any) -> str | None: ...


@runtime_checkable
class AfterAction(Protocol):
    """``after_action(trace, action, observation)``: called by the online policy after each action."""

    @property
    def after_action(self) -> Callable[[Trace, Action, Observation], None] | None: ...


CAPABILITIES: tuple[tuple[str, type], ...] = (
    ("value", HasValues),
    ("facts", ListsFacts),
    ("state", HasState),
    ("unknowns", HasUnknowns),
    ("reobserve", Reobserves),
    ("streams", HasStreams),
    ("planning_heuristic", HasHeuristic),
    ("after_action", AfterAction),
)


def capabilities(belief: object) -> list[str]:
    """The optional capabilities ``belief`` offers, by name (for logs and ``check_belief``)."""
    return [name for name, proto in CAPABILITIES if isinstance(belief, proto)]


def check_belief(domain: Domain, belief: object) -> None:
    """Called once when a run starts: a belief the engine cannot use is one clear error."""
    kind = type(belief).__name__
    if not isinstance(belief, Belief):
        raise ModelError(
            f"the belief {kind} has no update(action, observation); implement it or derive from "
            "nowplan.api.SymbolicBelief"
        )
    untested = sorted(n for n, p in domain.predicates.items() if p.test is None)
    if untested and not isinstance(belief, HasValues):
        raise ModelError(
            f"the belief {kind} has no value(key), so predicates without a test ({', '.join(untested[:3])}"
            f"{', …' if len(untested) > 3 else ''}) cannot be evaluated; add value() or give them tests"
        )
    log.info("belief %s offers: %s", kind, ", ".join(capabilities(belief)) or "update only")


def lists_facts(belief: object) -> bool:
    return isinstance(belief, ListsFacts)


def offers(obj: object, proto: Any) -> bool:
    """``isinstance(obj, proto)`` for a runtime-checkable protocol, remembered per (type, protocol).

    ``isinstance`` against such a protocol looks up each of its members on the object (10-20 µs),
    and the planner asks at every call (which searches a belief allows) and the progress guard after
    every action: 3-5 % of an HPN marsupial run's CPU (cProfile, single-20, two trials: 8,698 checks).
    A belief's capabilities are taken to be its class's (its methods, or the fields its constructor
    sets); for a class whose instances differ in them, call ``isinstance`` instead.
    """
    key = (type(obj), proto)
    hit = _OFFERS.get(key)
    if hit is None:
        if len(_OFFERS) >= 4096:
            _OFFERS.clear()
        hit = _OFFERS[key] = isinstance(obj, proto)
    return hit


_OFFERS: dict[tuple[type, Any], bool] = {}
