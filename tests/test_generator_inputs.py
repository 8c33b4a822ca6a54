"""A generator that raises is a domain error in one line, naming it and its unbound inputs.

Found by a held-out domain (examples/drone): ``fly(frm, to)``'s generator proposes where to fly
from given ``to``; the operator's other effect (the battery left) unified with a goal that binds no
``to``, the grounder called the generator (as it may: NAMO's read their inputs with ``bindings.get``)
and the run ended in a traceback from the domain's ``KeyError``.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterator
from typing import Any

from nowplan.api import Domain, Generator, Goal, Operator, Precondition, Predicate, State, SymbolicBelief, Var, atom, plan

to, frm = Var("to"), Var("frm")
calls: list[dict[Var, Any]] = []


def starts(bindings: dict[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    calls.append(dict(bindings))
    dest = bindings[to]  # its declared input: a KeyError if called without it
    for s in ("a", "b", "c"):
        if s != dest:
            yield {frm: s}


PREDICATES = {p.name: p for p in (Predicate("at", 1), Predicate("flown", 0))}
DOMAIN = Domain("gen", PREDICATES, (
    Operator("fly", (frm, to), (Precondition(atom("at", frm), 1),), (atom("at", to), atom("at", frm, value=False),
                                                                      atom("flown")),
             generators=(Generator("starts", (frm,), starts, (to,)),)),
))


def test_a_generator_that_raises_is_one_line_naming_it_and_its_unbound_inputs() -> None:
    import pytest  # noqa: PLC0415

    from nowplan.api import ModelError  # noqa: PLC0415

    b = SymbolicBelief(State([atom("at", "a")]))
    with pytest.raises(ModelError, match=r"generator starts of operator fly raised KeyError.*inputs \?to were unbound"):
        plan(DOMAIN, {}, b, Goal.of([atom("flown")], DOMAIN.rules))


def careful(bindings: dict[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    dest = bindings.get(to)
    if dest is None:
        return
    yield from starts(bindings, goal, belief, context)


CAREFUL = Domain("gen", PREDICATES, (
    Operator("fly", (frm, to), (Precondition(atom("at", frm), 1),), (atom("at", to), atom("at", frm, value=False),
                                                                      atom("flown")),
             generators=(Generator("starts", (frm,), careful, (to,)),)),
))


def test_a_generator_that_reads_its_inputs_with_get_grounds_nothing_without_them() -> None:
    calls.clear()
    b = SymbolicBelief(State([atom("at", "a")]))
    res = plan(CAREFUL, {}, b, Goal.of([atom("flown")], CAREFUL.rules))
    assert not res.solved and all(to in c for c in calls)


def test_the_same_generator_grounds_when_its_input_is_bound() -> None:
    calls.clear()
    b = SymbolicBelief(State([atom("at", "a")]))
    res = plan(DOMAIN, {}, b, Goal.of([atom("at", "c")], DOMAIN.rules))
    assert res.solved and res.plan is not None
    assert [(a.name, a.args) for a in res.plan.actions] == [("fly", ("a", "c"))]
    assert calls and all(c[to] == "c" for c in calls)


# -- the run's time limit, reached while HPN plans for the goal, is named as the run's -------------

FRESH = itertools.count()

def slow_starts(bindings: dict[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    import time  # noqa: PLC0415

    time.sleep(0.002)
    for _ in range(3):  # always new places: the search space has no end
        yield {frm: f"s{next(FRESH)}"}


SLOW = Domain("slow", PREDICATES, (
    Operator("fly", (frm, to), (Precondition(atom("at", frm), 1),), (atom("at", to), atom("at", frm, value=False)),
             generators=(Generator("starts", (frm,), slow_starts, (to,)),)),
))


def test_hpn_names_the_runs_time_limit_not_the_planners_clamped_one() -> None:
    from nowplan.api import Episode, Outcome, Problem, SymbolicWorld, parse_strategy, run_episode  # noqa: PLC0415

    init = State([atom("at", "a")])
    prob = Problem(SLOW, {}, init, Goal.of([atom("at", "z")], SLOW.rules), "slow")
    ep = Episode(prob, SymbolicWorld(SLOW, init), SymbolicBelief(init), "never found")
    m = run_episode(ep, parse_strategy("hpn", max_actions=10, time_limit=0.5), seed=0)
    assert m.outcome is Outcome.LIMIT
    assert m.reason.startswith("time limit of 0.5 s for the run reached while planning"), m.reason
