"""Running an operator's generators: the values that bind its free parameters (goal-directed grounding).

A generator sees the binding so far, the goal, the belief and the planning
context, and yields dictionaries of values for its outputs; the generators of
one operator run in order, each over every binding the ones before it made,
at most ``max_values`` values each.  A generator runs unless *all* its outputs
are bound; an output bound already (by the goal, through an effect) keeps its
value, and a proposal that gives it another value is skipped without counting
towards ``max_values`` (at most ``DRAW_FACTOR × max_values`` proposals are
drawn per call, so a generator that ignores its bound outputs cannot loop).
Each skip is recorded in ``misses`` so that a planner with no plan can say
which generator's proposals were all thrown away (:func:`misses_hint`).
A generator that raises gets one line naming it, its operator and the likely
fix (:func:`generator_error`), never a traceback.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from nowplan.core.atoms import Goal, Var
from nowplan.core.operators import Generator, Operator
from nowplan.errors import ModelError, NowplanError


DRAW_FACTOR = 8  # proposals drawn per call, in units of max_values (skipped ones included)


class Misses:
    """Calls whose proposals disagreed with outputs bound before the call, per (operator, generator)."""

    def __init__(self) -> None:
        self.calls: dict[tuple[str, str], tuple[int, tuple[str, ...]]] = {}  # -> (calls all skipped, bound outputs)

    def add(self, op: Operator, gen: Generator, bound: tuple[str, ...]) -> None:
        n, _ = self.calls.get((op.name, gen.name), (0, ()))
        self.calls[(op.name, gen.name)] = (n + 1, bound)

    def __bool__(self) -> bool:
        return bool(self.calls)


def misses_hint(misses: Misses) -> str:
    """The clause "; generator G of operator O ..." for a reason of no plan ("" when nothing was skipped)."""
    if not misses:
        return ""
    (op, gen), (n, bound) = max(misses.calls.items(), key=lambda kv: kv[1][0])
    more = f" (and {len(misses.calls) - 1} other generator(s))" if len(misses.calls) > 1 else ""
    return (f"; generator {gen} of operator {op} was called {n} time(s) with its output(s) "
            f"{', '.join(bound)} already bound (by the goal) and proposed none of those values{more}: "
            "a generator must keep the value of an output found bound in its bindings")


def run_generators(
    op: Operator, b: dict[Var, Any], goal: Goal, belief: Any, context: Any, max_values: int,
    misses: Misses | None = None,
) -> Iterator[dict[Var, Any]]:
    """The bindings extending ``b`` that ``op``'s generators give, in their order."""
    if not op.generators:
        yield b
        return

    def rec(i: int, cur: dict[Var, Any]) -> Iterator[dict[Var, Any]]:
        if i == len(op.generators):
            yield cur
            return
        gen = op.generators[i]
        if all(v in cur for v in gen.outputs):
            yield from rec(i + 1, cur)
            return
        # (a generator may run before its inputs are bound: an effect that binds none of them unified
        # with the goal; NAMO's read them with bindings.get.  One that fails is a domain error in one
        # line, not a traceback: a held-out drone's generator raised KeyError on its own input)
        try:
            values = iter(gen.fn(dict(cur), goal, belief, context))
        except NowplanError:
            raise
        except Exception as e:  # the domain's code: name it and the fix
            raise generator_error(gen, op, cur, e) from e
        n = drawn = skipped = 0
        while n < max_values and drawn < DRAW_FACTOR * max_values:
            try:
                vals = next(values)
            except StopIteration:
                break
            except NowplanError:
                raise
            except Exception as e:
                raise generator_error(gen, op, cur, e) from e
            drawn += 1
            if any(k in cur and cur[k] != v for k, v in vals.items()):
                skipped += 1  # it gave a bound output another value: not one of the max_values
                continue
            n += 1
            nxt = dict(cur)
            nxt.update(vals)
            yield from rec(i + 1, nxt)
        if skipped and not n and misses is not None:
            misses.add(op, gen, tuple(str(v) for v in gen.outputs if v in cur))

    try:
        yield from rec(0, b)
    finally:
        del rec  # it refers to itself: a cycle only the collector would free


def generator_error(gen: Generator, op: Operator, bound: Mapping[Var, Any], e: Exception) -> ModelError:
    """A domain's generator that raised, in one line: which, where, and the likely fix."""
    unbound = [str(v) for v in gen.inputs if v not in bound]
    return ModelError(
        f"generator {gen.name} of operator {op.name} raised {type(e).__name__}: {e}"
        + (f" (its inputs {', '.join(unbound)} were unbound: a generator may run before they are bound; "
           "read them with bindings.get and yield nothing then)" if unbound else "")
    )
