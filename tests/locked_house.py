"""A house, written against nowplan's public API as a user would (a test domain).

Rooms joined by doors; one door is locked and its key lies elsewhere; some doors are
sticky (going through fails with probability 0.2); the mug is not where the robot
believes it is, and is found by looking.  Criticalities make it hierarchical: where
the objects are (3) before where the robot is (2) before which doors are unlocked (1),
so the key-fetching sub-plan appears only when a move through the locked door is
refined.

    garage --d_gk(locked)-- kitchen --d_hk-- hall --d_hl-- living --d_ls-- study
                                              |                             |
                                            d_hb(sticky)               d_bs(sticky)
                                              |                             |
                                            bedroom ------------------------+

The robot starts in the hall; the key is in the study; the mug is believed to be in the
bedroom but is in the garage (or, by seed, another room); the goal is the mug in the
living room.
"""

from __future__ import annotations

import random

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import AtMostOne, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Action, Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.registry import Episode
from nowplan.worlds.base import Observation

OBJ, ROBOT, LOCK = 3, 2, 1  # criticalities

o, r, r2, d, k = (Var(n) for n in ("o", "r", "r2", "d", "k"))

PREDICATES = {
    "door": Predicate("door", 3, ("door", "room", "room")),
    "unlocked": Predicate("unlocked", 1, ("door",)),
    "key_for": Predicate("key_for", 2, ("item", "door")),
    "at": Predicate("at", 2, (None, "room")),  # an item's or the robot's room
    "holding": Predicate("holding", 1, ("item",)),
    "located": Predicate("located", 1, ("item",)),
}


def _p(a: object, c: int) -> Precondition:
    return Precondition(a, c)  # type: ignore[arg-type]


OPERATORS = (
    Operator("move", (d, r, r2),
             (_p(atom("at", "robot", r), ROBOT), _p(atom("door", d, r, r2), ROBOT), _p(atom("unlocked", d), LOCK)),
             (atom("at", "robot", r2), atom("at", "robot", r, value=False)),
             param_types=("door", "room", "room")),
    Operator("unlock", (d, k, r, r2),
             (_p(atom("at", "robot", r), LOCK), _p(atom("door", d, r, r2), LOCK), _p(atom("holding", k), LOCK),
              _p(atom("key_for", k, d), LOCK)),
             (atom("unlocked", d),),
             param_types=("door", "item", "room", "room")),
    Operator("look", (o, r),
             (_p(atom("at", o, r), OBJ), _p(atom("at", "robot", r), ROBOT)),
             (atom("located", o),),
             param_types=("item", "room")),
    Operator("pick", (o, r),
             (_p(atom("at", o, r), OBJ), _p(atom("located", o), OBJ), _p(atom("at", "robot", r), ROBOT)),
             (atom("holding", o), atom("at", o, r, value=False)),
             param_types=("item", "room")),
    Operator("place", (o, r),
             (_p(atom("holding", o), OBJ), _p(atom("at", "robot", r), ROBOT)),
             (atom("at", o, r), atom("holding", o, value=False)),
             param_types=("item", "room")),
)

# an item (or the robot) is in one room or held, never two
DOMAIN = Domain("house", PREDICATES, OPERATORS, types={"room": None, "door": None, "item": None, "agent": None},
                conflicts=(AtMostOne(("at", "holding")),))

ROOMS = ("hall", "kitchen", "garage", "living", "study", "bedroom")
DOORS = {"d_hk": ("hall", "kitchen"), "d_gk": ("kitchen", "garage"), "d_hl": ("hall", "living"),
         "d_ls": ("living", "study"), "d_hb": ("hall", "bedroom"), "d_bs": ("bedroom", "study")}
LOCKED = "d_gk"
STICKY = frozenset({"d_hb", "d_bs", "d_hk"})
BELIEVED = "bedroom"  # where the robot thinks the mug is
SEARCH_ORDER = ("bedroom", "study", "kitchen", "garage")  # where it looks next after a miss


class HouseWorld:
    """The true house: sticky doors fail at ``sticky_p``; a look reports the room's items."""

    def __init__(self, state: State, seed: int, sticky_p: float = 0.2) -> None:
        self.state = state
        self.rng = random.Random(seed)
        self.sticky_p = sticky_p

    def true_state(self) -> State:
        return self.state

    def execute(self, action: Action) -> Observation:
        ok = all(DOMAIN.holds(p, self.state) for p in action.preconditions(None))
        info: dict[str, object] = {} if ok else {"reason": "preconditions false in the house"}
        if ok and action.name == "move" and action.args[0] in STICKY and self.rng.random() < self.sticky_p:
            ok, info = False, {"reason": f"door {action.args[0]} stuck"}
        if ok:
            self.state = self.state.apply(action.effects())
        seen = None
        if action.name == "look":
            room = next(a[1] for a in self.state.facts("at") if a[0] == "robot")
            seen = (room, frozenset(a[0] for a in self.state.facts("at") if a[1] == room))
        return Observation(ok, seen, (), info)


class HouseBelief(SymbolicBelief):
    """The robot's facts; a look in a room corrects where the items in it are.

    A look that misses an item believed there moves the belief to the next room of
    ``SEARCH_ORDER`` not yet searched (the most likely place left).
    """

    def __init__(self, state: State) -> None:
        super().__init__(state)
        self.searched: set[str] = set()

    def update(self, action: Action, observation: Observation) -> None:
        if observation.success:
            self.state = self.state.apply(action.effects())
        if action.name != "look" or observation.data is None:
            return
        room, items = observation.data
        self.searched.add(room)
        changes = []
        for item in items:
            if item != "robot":
                changes += [atom("at", item, x, value=False) for x in ROOMS] + [atom("at", item, room)]
        for (item, where) in list(self.state.facts("at")):
            if where == room and item not in items and item != "robot":
                nxt = next((x for x in SEARCH_ORDER if x not in self.searched), None)
                changes.append(atom("at", item, room, value=False))
                changes.append(atom("located", item, value=False))
                if nxt is not None:
                    changes.append(atom("at", item, nxt))
        self.state = self.state.apply(changes)

    def fingerprint(self) -> object:
        return (self.state, frozenset(self.searched))


def episode(seed: int, sticky_p: float = 0.2) -> Episode:
    rng = random.Random(seed)
    mug_room = rng.choice(("garage", "study", "kitchen"))
    static = [atom("door", dd, a, b) for dd, (a, b) in DOORS.items()]
    static += [atom("door", dd, b, a) for dd, (a, b) in DOORS.items()]
    static += [atom("unlocked", dd) for dd in DOORS if dd != LOCKED]
    static += [atom("key_for", "key", LOCKED), atom("at", "key", "study"), atom("at", "robot", "hall")]
    truth = State([*static, atom("at", "mug", mug_room)])
    believed = State([*static, atom("at", "mug", BELIEVED)])
    objects: dict[str, str | None] = {x: "room" for x in ROOMS}
    objects.update({x: "door" for x in DOORS})
    objects.update({"key": "item", "mug": "item", "robot": "agent"})
    prob = Problem(DOMAIN, objects, believed, Goal.of([atom("at", "mug", "living")]), f"house-s{seed}")
    return Episode(prob, HouseWorld(truth, seed + 1, sticky_p), HouseBelief(believed),
                   f"house: mug in the {mug_room}, believed in the {BELIEVED}")


def main(argv: list[str] | None = None) -> int:
    """``python tests/locked_house.py STRATEGY[,STRATEGY…] [FIRST_SEED LAST_SEED [TIME_LIMIT]]``:
    success per strategy over the seeds (the figures of tests/test_house.py's sweep)."""
    import sys

    from nowplan.acting.run import run_episode
    from nowplan.acting.strategy import parse_strategy

    args = sys.argv[1:] if argv is None else argv
    first, last = (int(args[1]), int(args[2])) if len(args) > 2 else (0, 19)
    limit = float(args[3]) if len(args) > 3 else 60.0
    for name in args[0].split(","):
        runs = [(s, run_episode(episode(s), parse_strategy(name, time_limit=limit), seed=s))
                for s in range(first, last + 1)]
        ok = sum(m.outcome.value == "reached" for _, m in runs)
        bad = "; ".join(f"seed {s}: {m.outcome.value} after {m.actions} actions ({m.reason[:60]})"
                        for s, m in runs if m.outcome.value != "reached")
        print(f"{name}: {ok}/{len(runs)} reached, mean actions "
              f"{sum(m.actions for _, m in runs) / len(runs):.1f}" + (f"; {bad}" if bad else ""))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
