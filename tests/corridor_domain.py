"""A corridor a-b-c-d, written against nowplan's public API (a test domain for loops).

The door c-d is locked and its key lies at a.  The abstract plan (locks have criticality 1)
is a->b->c->d; refining c->d fetches the key, walking back through b, where the abstract
plan's earlier pre-image holds again.  Serendipity that resumed there dropped the key
sub-plan, and replanning from the root after every action turned back toward the door each
time: both looped until a budget ran out (issue 14).
"""

from __future__ import annotations

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import AtMostOne, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.registry import Episode
from nowplan.worlds.symbolic import SymbolicWorld


def corridor() -> Episode:
    x, y = Var("x"), Var("y")
    preds = {"at": Predicate("at", 1), "link": Predicate("link", 2), "open": Predicate("open", 2),
             "has_key": Predicate("has_key", 0), "key_at": Predicate("key_at", 1)}
    ops = (
        Operator("go", (x, y), (Precondition(atom("at", x), 2), Precondition(atom("link", x, y), 2),
                                Precondition(atom("open", x, y), 1)),
                 (atom("at", y), atom("at", x, value=False))),
        Operator("take", (x,), (Precondition(atom("at", x), 1), Precondition(atom("key_at", x), 1)),
                 (atom("has_key"), atom("key_at", x, value=False))),
        Operator("unlock", (x, y), (Precondition(atom("at", x), 1), Precondition(atom("has_key"), 1),
                                    Precondition(atom("link", x, y), 1)),
                 (atom("open", x, y),)),
    )
    dom = Domain("corridor", preds, ops, conflicts=(AtMostOne(("at",)),))
    rooms = "abcd"
    facts = [atom("at", "a"), atom("key_at", "a")]
    for p, q in zip(rooms, rooms[1:]):
        facts += [atom("link", p, q), atom("link", q, p)]
        if (p, q) != ("c", "d"):
            facts += [atom("open", p, q), atom("open", q, p)]
    init = State(facts)
    prob = Problem(dom, {r: None for r in rooms}, init, Goal.of([atom("at", "d")]))
    return Episode(prob, SymbolicWorld(dom, init), SymbolicBelief(init))


def main() -> int:
    """``python tests/corridor_domain.py STRATEGY[,STRATEGY…]``: outcome and actions of each."""
    import sys

    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy

    for name in sys.argv[1].split(","):
        m = run_episode(corridor(), parse_strategy(name, max_actions=200, time_limit=60.0))
        print(f"{name}: {m.outcome.value} after {m.actions} actions {m.reason}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
