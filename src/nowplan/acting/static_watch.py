"""Static facts the world changed: plans made assuming them are made again.

A predicate no operator changes is *static*: its facts are checked when actions are grounded and
left out of every pre-image (``planning/preimage.static_drop``), so no plan's pre-images mention
them.  A world may still change such a fact by itself (a held-out ferry's passenger changes the
destination she ``wants``; no operator changes it).  Then a plan made before says its steps
apply while one of them cannot: under RCHPN the step after the highest true pre-image was chosen
again and again, failing until the stall guard ended the run, and every strategy ran the stale
step once.  The executive keeps a :class:`StaticWatch`; after an observation that reports an
exogenous change, the static facts that changed in the belief are looked up in the steps still
to come of every plan on the stack (:func:`stale_frame`): the plan nearest the root with a step
whose precondition on them fails now is dropped with the plans above it, and the plan below it
refines its step again.  A change no remaining step depends on (an alarm a trigger hears, a cost)
drops nothing: the reconsidering mechanisms judge it as before.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING, Any

from nowplan.core.domain import Domain
from nowplan.planning.preimage import static_drop

if TYPE_CHECKING:
    from nowplan.acting.hpn import Executive

MAX_NAMED = 3  # changed facts named in the trace note


class StaticWatch:
    """The belief's facts of the static predicates kept out of pre-images, as last seen."""

    def __init__(self, domain: Domain, belief: Any) -> None:
        self.predicates = tuple(sorted(static_drop(domain, belief)))
        self._seen = self._facts(belief)

    def _facts(self, belief: Any) -> dict[str, frozenset[tuple[Any, Any]]]:
        out: dict[str, frozenset[tuple[Any, Any]]] = {}
        for p in self.predicates:
            # with each fact's value: a valued static fluent may change its value, not its arguments
            out[p] = frozenset((args, belief.value((p, args))) for args in belief.facts(p))
        return out

    def changed(self, belief: Any, exogenous: bool) -> list[tuple[str, tuple[Any, ...]]]:
        """After an observation (``exogenous``: it reported a change the world made): the static facts
        that changed since the last look, as ``(predicate, args)``; ``[]`` when none did or none could."""
        if not exogenous or not self.predicates:
            return []
        now = self._facts(belief)
        out: list[tuple[str, tuple[Any, ...]]] = []
        for p in self.predicates:
            for args in sorted({args for args, _ in now[p] ^ self._seen[p]}, key=repr):
                out.append((p, args))
        self._seen = now
        return out

    def after_observation(self, ex: Executive, exogenous: bool) -> None:
        """After an action's observation: where a step still to come of a plan on ``ex``'s stack needs a
        static fact the world changed, drop the plan nearest the root with such a step and those above
        it, and have the plan below refine its step again (as after a backtrack)."""
        changed = self.changed(ex.belief, exogenous)
        k = stale_frame(ex.stack, ex.domain, ex.truth, changed) if changed else None
        if k is None:
            return
        why = (f"the world changed static fact(s) {describe(changed)}, which no operator changes and so no "
               f"pre-image names; a step of plan {ex.stack[k].plan_id} needs them")
        ex.trace.emit("note", plan_id=ex.stack[k].plan_id, text=f"executive: {why}; it is made again")
        ex.unwind(k, "static facts changed")
        ex.request_replan("static", why)


def stale_frame(stack: Sequence[Any], domain: Domain, truth: Any, changed: Iterable[tuple[str, tuple[Any, ...]]]) -> int | None:
    """The index of the plan nearest the root (``stack[0]``) with a step still to come (from its current
    one on) whose precondition on a ``changed`` predicate fails in ``truth``, or None."""
    preds = {p for p, _ in changed}
    for k, f in enumerate(stack):
        for step in f.plan.steps[max(f.i, 1):]:
            a = step.action
            if a is None:
                continue
            for pre in a.preconditions(None):
                if pre.predicate in preds and not domain.holds(pre, truth):
                    return k
    return None


def describe(changed: Sequence[tuple[str, tuple[Any, ...]]]) -> str:
    """``wants(p2, cove), wants(p2, pier)`` (at most :data:`MAX_NAMED`, then how many more)."""
    texts = [f"{p}({', '.join(map(str, args))})" for p, args in changed]
    head = ", ".join(texts[:MAX_NAMED])
    more = len(texts) - MAX_NAMED
    return head + (f" and {more} more" if more > 0 else "")
