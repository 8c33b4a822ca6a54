"""Running an operator's generators: the values that bind its free parameters (goal-directed grounding).

A generator sees the binding so far, the goal, the belief and the planning
context, and yields dictionaries of values for its outputs; the generators of
one operator run in order, each over every binding the ones before it made,
at most ``max_values`` values each.  A generator that raises gets one line
naming it, its operator and the likely fix (:func:`generator_error`), never a
traceback.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from nowplan.core.atoms import Goal, Var
from nowplan.core.operators import Generator, Operator
from nowplan.errors import ModelError, NowplanError


def run_generators(
    op: Operator, b: dict[Var, Any], goal: Goal, belief: Any, context: Any, max_values: int
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
        n = 0
        while n < max_values:
            try:
                vals = next(values)
            except StopIteration:
                break
            except NowplanError:
                raise
            except Exception as e:
                raise generator_error(gen, op, cur, e) from e
            n += 1
            nxt = dict(cur)
            if any(k in nxt and nxt[k] != v for k, v in vals.items()):
                continue
            nxt.update(vals)
            yield from rec(i + 1, nxt)

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
