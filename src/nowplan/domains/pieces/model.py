"""The shuffled-pieces domain in the core model, for the regression planner.

Fluents: ``has(cell, kind)``, ``empty(cell)`` and ``arm_at(cell)``.
Primitives (seed 003 Table 3): ``move_arm(a, b)`` and ``move_piece(k, a, b)``
(the arm carries a piece of kind ``k`` from ``a`` to ``b``); both cost the
arm's straight-line travel.  Criticalities make it hierarchical in HPN's
way: at the top level only where the pieces are matters (a move needs the
piece at ``a`` and ``b`` empty); the arm's position is added one level down,
so arm moves appear only when a piece move is refined.  The domain brings
the seed's means-ends planner as its own (``Domain.planner``, used by the
executive under the ``domain-planner`` switch; see
:mod:`nowplan.domains.pieces.planner`).

The goal of a problem is ``has(c, k)`` for each goal cell: pieces are
interchangeable within a kind, and surplus pieces may stand anywhere that
is not a goal cell of another kind.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from nowplan.acting.monitor_support import MonitorSupport
from nowplan.core.atoms import Atom, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.domains.pieces.board import KINDS, Board, distance

PIECE = 1  # criticality of piece-placement preconditions
ARM = 0  # criticality of the arm's position

k, a, b = Var("k"), Var("a"), Var("b")

PREDICATES = {
    "has": Predicate("has", 2, ("cell", "kind")),
    "empty": Predicate("empty", 1, ("cell",)),
    "arm_at": Predicate("arm_at", 1, ("cell",)),
}


def _travel(bindings: Mapping[Var, object], belief: object) -> float:
    return distance(str(bindings[a]), str(bindings[b]))


# negative effects first: for a == b the positive one wins when effects are applied in order
OPERATORS = (
    Operator(
        "move_arm", (a, b),
        (Precondition(atom("arm_at", a), ARM),),
        (atom("arm_at", a, value=False), atom("arm_at", b)),
        cost=_travel, param_types=("cell", "cell"),
    ),
    Operator(
        "move_piece", (k, a, b),
        (Precondition(atom("has", a, k), PIECE), Precondition(atom("empty", b), PIECE),
         Precondition(atom("arm_at", a), ARM)),
        (atom("has", a, k, value=False), atom("empty", b, value=False), atom("arm_at", a, value=False),
         atom("has", b, k), atom("empty", a), atom("arm_at", b)),
        cost=_travel, param_types=("kind", "cell", "cell"),
    ),
)


def one_occupant(x: Atom, y: Atom) -> bool:
    """A cell holds one piece or is empty; the arm is at one cell."""
    if x.value is not True or y.value is not True or x.key == y.key:
        return False
    if x.predicate == "arm_at" and y.predicate == "arm_at":
        return True
    if x.predicate in ("has", "empty") and y.predicate in ("has", "empty"):
        return x.args[0] == y.args[0]
    return False


def _means_ends(*args: Any, **kwargs: Any) -> Any:
    """The seed's means-ends planner for the executive's ``domain-planner`` switch."""
    from nowplan.domains.pieces.planner import means_ends_for_executive  # it imports this module

    return means_ends_for_executive(*args, **kwargs)


def _support() -> MonitorSupport:
    """The monitor's support (seed 003): model distance, the means-ends planner, arm re-routing.

    Its functions live in modules that import this one, so they are looked up on first use.
    """

    def planner(*args: Any, **kwargs: Any) -> Any:
        from nowplan.domains.pieces.meansends import plan_means_ends

        return plan_means_ends(*args, **kwargs)

    def adapt(actions: Any, state: Any) -> Any:
        from nowplan.domains.pieces.support import start_arm_from_here

        return start_arm_from_here(actions, state)

    def distance(a: Any, b: Any) -> float:
        from nowplan.domains.pieces.support import model_distance

        return model_distance(a, b)

    return MonitorSupport(distance=distance, planner=planner, adapt=adapt, ignore=frozenset({"arm_at"}))


DOMAIN = Domain(
    "pieces", PREDICATES, OPERATORS, {"cell": None, "kind": None},
    constants={kd: "kind" for kd in KINDS}, conflicts=(one_occupant,), planner=_means_ends,
    monitor=_support(),
)


def goal_of(placement: Mapping[str, str]) -> Goal:
    """``has(c, k)`` for every goal cell."""
    return Goal.of([atom("has", c, kd) for c, kd in placement.items()], DOMAIN.rules)


def placement_of(goal: Goal) -> dict[str, str]:
    return {str(x.args[0]): str(x.args[1]) for x in goal.atoms if x.predicate == "has" and x.value is True}


def problem(init: Board, goal_placement: Mapping[str, str], name: str = "pieces") -> Problem:
    objects: dict[str, str | None] = {c: "cell" for c in init.geometry.cells}
    return Problem(DOMAIN, objects, init.to_state(), goal_of(goal_placement), name)


def goal_reached(board: Board, goal_placement: Mapping[str, str]) -> bool:
    return all(board.at(c) == kd for c, kd in goal_placement.items())
