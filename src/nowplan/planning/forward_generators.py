"""Generators in the forward task: the values of generators that read nothing of the goal.

A forward search grounds its task once per call, from the belief and without a goal, so it can
take an operator with generators only when each generator declares that its values do not depend
on the goal (``Generator(reads=reads_nothing)``: the same values in every subgoal, the property
the lazy relaxation relies on too) and binds parameters of the operator.  Grounding then joins the
operator's preconditions as usual, each parameter a generator binds enumerated from the facts or
by type, and keeps a binding only where the regression grounder could make it: for some effect
of the operator, the generators, run on the binding of the other parameters and of the outputs
that effect names (as unifying it with a target binds them) and on the belief (context ``None``),
propose the rest of its values (at most ``max_values`` each, as the regression grounder draws
them; :func:`nowplan.planning.generators_run.run_generators`).  A
generator that proposes a value that is not an object of the problem (a pose, a number) cannot be
enumerated that way, and one that fails without a goal and a planning context may need them:
either way the call leaves the forward search (:class:`NotEnumerable`) and the regression search
plans, as it did for every domain with generators before.

Found on the held-out tidy house (``benchmarks/results/heldout14/README.md``, finding 2): its
``spot`` generator proposes free floor spots, objects of the problem, and declares
``reads_nothing``; flat planning took 0.07 CPU s without the generator and ran out of its 10 s
with it (the regression search with a lazy relaxation).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from nowplan.core.atoms import Goal
from nowplan.core.domain import Domain
from nowplan.core.operators import Operator, reads_nothing
from nowplan.errors import NowplanError
from nowplan.planning.generators_run import Misses, run_generators

_NO_GOAL = Goal(frozenset())


class NotEnumerable(Exception):
    """A generator proposed a value the forward task cannot enumerate (the regression search plans)."""


def generators_unsupported(domain: Domain) -> str | None:
    """Why the forward task cannot take the domain's generators, or ``None`` if it can."""
    for op in domain.operators:
        for g in op.generators:
            if g.reads is not reads_nothing:
                return (f"operator {op.name} has a generator ({g.name}) that does not declare "
                        "reads=reads_nothing (the forward task is grounded without a goal)")
            missing = [str(v) for v in g.outputs if v not in op.params]
            if missing:
                return f"generator {g.name} of operator {op.name} binds {', '.join(missing)}, not a parameter"
    return None


class GeneratorFilter:
    """Which bindings of an operator with generators the regression grounder could make, from one belief.

    The regression grounder binds an achiever's parameters by unifying one of its effects with the
    target atom, and runs a generator only for outputs that effect left unbound (a proposal that
    disagrees with a bound output is skipped).  So a binding is kept when, for some effect, the
    generators run on the other parameters and the outputs that effect names propose the rest of
    its values; an effect that names every output keeps every binding (no generator runs).
    """

    def __init__(self, belief: Any, objects: frozenset[Any], max_values: int) -> None:
        self.belief = belief
        self.objects = objects
        self.max_values = max_values
        self.misses = Misses()  # proposals skipped for disagreeing with a bound output (named on failure)
        self._covers: dict[str, list[tuple[tuple[int, ...], tuple[int, ...]]] | None] = {}
        self._allowed: dict[tuple[str, tuple[int, ...], tuple[Any, ...]], frozenset[tuple[Any, ...]]] = {}

    def _split(self, op: Operator) -> list[tuple[tuple[int, ...], tuple[int, ...]]] | None:
        """Per distinct effect, the positions of the outputs it leaves to the generators and of the
        parameters bound before they run (``None``: an effect names every output, so every binding
        is kept); effects that name more outputs first."""
        if op.name not in self._covers:
            outs = {v for g in op.generators for v in g.outputs}
            opos = [i for i, p in enumerate(op.params) if p in outs]
            splits: list[tuple[tuple[int, ...], tuple[int, ...]]] = []
            every = False  # an effect, unified with a target, binds every output: no generator runs
            for e in sorted(op.effects, key=lambda e: -len({t for t in e.args if t in outs})):
                named = set(e.args)
                rest = tuple(i for i in opos if op.params[i] not in named)
                if not rest:
                    every = True
                    break
                split = (rest, tuple(i for i in range(len(op.params)) if i not in rest))
                if split not in splits:
                    splits.append(split)
            self._covers[op.name] = None if every else splits
        return self._covers[op.name]

    def accepts(self, op: Operator, args: Sequence[Any]) -> bool:
        """Could the regression grounder make ``op`` with ``args`` (see the class docstring)?"""
        splits = self._split(op)
        if splits is None:
            return True
        for rest, bound in splits:
            key = (op.name, rest, tuple(args[i] for i in bound))
            allowed = self._allowed.get(key)
            if allowed is None:
                b = {op.params[i]: args[i] for i in bound}
                found: set[tuple[Any, ...]] = set()
                try:
                    for full in run_generators(op, b, _NO_GOAL, self.belief, None, self.max_values, self.misses):
                        vals = tuple(full.get(op.params[i]) for i in rest)
                        for v in vals:
                            if v not in self.objects:
                                raise NotEnumerable(f"a generator of operator {op.name} proposed {v!r}, not an "
                                                    "object of the problem")
                        found.add(vals)
                except NowplanError as e:  # (one that needs a planning context: the regression search has one)
                    raise NotEnumerable(f"a generator of operator {op.name} failed without a goal and context "
                                        f"({e})") from None
                allowed = self._allowed[key] = frozenset(found)
            if tuple(args[i] for i in rest) in allowed:
                return True
        return False
