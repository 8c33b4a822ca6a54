"""A planner call frees its memory when it returns, not at the collector's next pass.

The search's helpers held bound methods of the search, and the grounder's recursive
closures referred to themselves: every call's nodes, tables and explorations stayed
as cyclic garbage until a full pass of the collector found them (docs/peephole.md,
RCHPN's fifth pass).  These tests count what the collector finds after a call.
"""

from __future__ import annotations

import gc
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from nowplan.core.atoms import Goal, Var, atom
from nowplan.core.domain import Domain, Predicate
from nowplan.core.levels import LevelMap
from nowplan.core.operators import Generator, Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.marsupial.model import PLANNER
from nowplan.domains.marsupial.scenarios import episode
from nowplan.planning.grounding import Grounder
from nowplan.planning.regression import plan

pytestmark = pytest.mark.timeout(120)


def _collected_after(fn: Callable[[], object]) -> int:
    """Objects the collector finds unreachable after ``fn()`` ran with the collector paused."""
    gc.collect()
    was = gc.isenabled()
    gc.disable()
    try:
        fn()
        return gc.collect()
    finally:
        if was:
            gc.enable()


@pytest.mark.parametrize("regime,n", [("both", 3), ("single", 4)])
def test_a_marsupial_call_leaves_no_cyclic_garbage(regime: str, n: int) -> None:
    ep = episode(regime, n, 0)
    p = ep.problem
    levels = LevelMap(p.domain.top_level)
    results = []

    def call() -> None:
        results.append(plan(p.domain, p.objects, ep.belief, p.goal, levels, PLANNER))

    assert _collected_after(call) == 0
    assert results[0].solved and results[0].expanded > 0
    # the same call again gives the same plan (nothing it needed was freed early)
    again = plan(p.domain, p.objects, ep.belief, p.goal, levels, PLANNER)
    assert again.plan is not None and results[0].plan is not None
    assert [s.action for s in again.plan.steps] == [s.action for s in results[0].plan.steps]


def test_groundings_abandoned_early_leave_no_cycle() -> None:
    """The grounder's recursive iterators (generators, then the static join) dropped before
    their end, as a search that needed one instance drops them, are freed too."""
    to, via, mid = Var("to"), Var("via"), Var("mid")
    preds = {"at": Predicate("at", 1), "road": Predicate("road", 2)}

    def pick(b: object, goal: object, belief: object, ctx: object) -> Iterator[dict[Var, Any]]:
        yield from ({via: x} for x in ("x", "w"))

    op = Operator("go", (to, via, mid), (Precondition(atom("road", via, mid)),), (atom("at", to),),
                  generators=(Generator("via", (via,), pick),))
    dom = Domain("roads", preds, (op,))
    state = State([atom("road", "x", "y"), atom("road", "x", "z"), atom("road", "w", "y")])
    g = Grounder(dom, {"x": None, "y": None, "z": None, "w": None, "b": None}, state)
    goal = Goal.of([atom("at", "b")])
    its: list[Iterator[Any]] = [g._run_generators(op, {to: "b"}, goal), g._fill(op, {to: "b", via: "x"})]
    firsts = [next(it) for it in its]  # each stopped inside its recursion
    assert firsts == [{to: "b", via: "x"}, {to: "b", via: "x", mid: "y"}]
    assert _collected_after(its.clear) == 0
