"""Deferred stream evaluation (seed 004 VII).

After a candidate plan is found, its :class:`~nowplan.planning.streams.Optimistic`
placeholders must be bound.  Without deferral every placeholder is bound now
(the Focused algorithm does not stop before all hypothetical values are
bound).  With deferral only those needed to perform the *first* action, or
produced by a stream marked never-defer or not deferrable, are bound — and,
recursively, the placeholders those depend on; the rest are left for the
next replanning, which re-derives them from the new belief anyway.
"""

from __future__ import annotations

import logging
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from nowplan.core.operators import Action
from nowplan.planning.streams import Optimistic, StreamSet

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Resolution:
    """The plan with the scheduled placeholders bound, or the one that failed."""

    actions: tuple[Action, ...]
    ok: bool
    evaluated: int
    deferred: int
    failed: Optimistic | None = None


def _placeholders(value: Any) -> list[Optimistic]:
    if isinstance(value, Optimistic):
        out = [value]
        for v in value.inputs:
            out.extend(_placeholders(v))
        return out
    return []


def schedule(actions: Sequence[Action], streams: StreamSet, deferred: bool) -> set[Optimistic]:
    """The placeholders to bind now (first action's, never-deferred ones, and their inputs)."""
    now: set[Optimistic] = set()
    for i, act in enumerate(actions):
        for arg in act.args:
            for ph in _placeholders(arg):
                if not deferred or i == 0 or not streams[ph.stream].deferrable:
                    now.add(ph)
    # propagate: a placeholder needed now needs its own placeholder inputs
    stack = list(now)
    while stack:
        ph = stack.pop()
        for v in ph.inputs:
            for dep in _placeholders(v):
                if dep not in now:
                    now.add(dep)
                    stack.append(dep)
    return now


def resolve(actions: Sequence[Action], streams: StreamSet, belief: Any, deferred: bool) -> Resolution:
    """Bind the scheduled placeholders in plan order; stop at the first stream that fails."""
    todo = schedule(actions, streams, deferred)
    bound: dict[Optimistic, Any] = {}
    out: list[Action] = []
    n_deferred = 0

    def value(v: Any, earlier: tuple[Action, ...]) -> Any:
        if not isinstance(v, Optimistic):
            return v
        if v in bound:
            return bound[v]
        if v not in todo:
            return v
        inputs = tuple(value(x, earlier) for x in v.inputs)
        got = streams.evaluate(v.stream, belief, earlier, *inputs)
        bound[v] = got
        return got

    for act in actions:
        earlier = tuple(out)
        args = []
        for a in act.args:
            b = value(a, earlier)
            if b is None:
                return Resolution(tuple(out), False, len(bound), n_deferred, a if isinstance(a, Optimistic) else None)
            n_deferred += isinstance(b, Optimistic)
            args.append(b)
        out.append(Action(act.operator, tuple(args)))
    return Resolution(tuple(out), True, len(bound), n_deferred)
