"""What the robot believes: the house as it last saw each room.

The robot sees only its own room.  A thing it expected in the room and does not see there (the
cat took it) is *lost*: it is guessed on a free floor spot of a room next to where it was last
seen, and each room looked into without it is struck off its candidates (all rooms again when
none are left): the robot searches by going where the thing most likely is.
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping, Sequence

from nowplan.api import Action, Atom, Observation, State, SymbolicBelief, atom

from tidy_domain.world import Seen


def house_state(statics: Sequence[Atom], robot: str, held: str | None, doors: Mapping[str, tuple[bool, bool]],
                things: Mapping[str, tuple[str, str]], supports: Sequence[str]) -> State:
    """The state of a house: the statics, the robot, the doors, each thing's support and room,
    and ``clear`` for every support nothing lies on."""
    facts = list(statics) + [atom("robot_in", robot), atom("holding", held) if held else atom("hand_empty")]
    for dr, (is_open, unlocked) in doors.items():
        facts += [atom("open", dr)] * is_open + [atom("unlocked", dr)] * unlocked
    below = set()
    for t, (sup, rm) in things.items():
        facts += [atom("on", t, sup), atom("in", t, rm)]
        below.add(sup)
    facts += [atom("clear", s) for s in supports if s not in below]
    return State(facts)


class TidyBelief(SymbolicBelief):
    """A point belief: the initial map, overwritten room by room by what the robot sees."""

    def __init__(self, *, statics: Sequence[Atom], robot: str, doors: Mapping[str, tuple[bool, bool]],
                 things: Mapping[str, tuple[str, str]], supports: Sequence[str],
                 spots: Mapping[str, str], neighbours: Mapping[str, Sequence[str]]) -> None:
        self.statics, self.supports = list(statics), list(supports)
        self.spots = dict(spots)  # floor spot: its room
        self.neighbours = {k: list(v) for k, v in neighbours.items()}
        self.robot = robot
        self.held: str | None = None
        self.doors, self.things = dict(doors), dict(things)
        self.lost: dict[str, list[str]] = {}  # thing: the rooms it may be in, best first
        super().__init__(self._state())

    def _state(self) -> State:
        return house_state(self.statics, self.robot, self.held, self.doors, self.things, self.supports)

    def fingerprint(self) -> Hashable:
        """The believed state and where lost things are still looked for."""
        return (self.state, tuple(sorted((t, tuple(c)) for t, c in self.lost.items())))

    def _candidates(self, last: str, not_here: str) -> list[str]:
        near = [x for x in self.neighbours[last] if x != not_here]
        rest = sorted(x for x in self.neighbours if x not in near and x != not_here)
        return near + rest

    def update(self, action: Action, observation: Observation) -> None:
        seen = observation.data
        if not isinstance(seen, Seen):
            return
        room = self.robot = seen.room
        here = dict(seen.things)
        if self.held and self.held != seen.holding and self.held not in here:
            # put down (or dropped) and gone before it was seen: the cat took it (a first version
            # forgot such a thing altogether, and its goal became "unreachable even ignoring deletes")
            self.lost[self.held] = self._candidates(room, room)
        self.held = seen.holding
        if observation.success:  # what the robot did to a door out of sight (call_owner): a first
            # version believed only what it saw, and called the owner again and again (cost 40 each)
            for a in action.effects():
                if a.predicate in ("open", "unlocked"):
                    is_open, unlocked = self.doors[str(a.args[0])]
                    self.doors[str(a.args[0])] = ((a.value is True) if a.predicate == "open" else is_open,
                                                  (a.value is True) if a.predicate == "unlocked" else unlocked)
        for dr, is_open, unlocked in seen.doors:
            self.doors[dr] = (is_open, unlocked)
        if seen.holding:
            self.things.pop(seen.holding, None)
            self.lost.pop(seen.holding, None)
        for t, (_, rm) in list(self.things.items()):
            if rm == room and t not in here and t not in self.lost:
                self.lost[t] = self._candidates(room, room)
        for t in here:
            self.things[t] = (here[t], room)
            self.lost.pop(t, None)
        for t, cands in self.lost.items():
            self.things.pop(t, None)
            if room in cands:
                cands.remove(room)
            if not cands:
                cands.extend(self._candidates(room, room))
        taken = {sup for sup, _ in self.things.values()}
        for t, cands in sorted(self.lost.items()):
            for rm in cands:
                free = sorted(s for s, srm in self.spots.items() if srm == rm and s not in taken)
                if free:
                    self.things[t] = (free[0], rm)
                    taken.add(free[0])
                    break
        self.state = self._state()


__all__ = ["TidyBelief", "house_state"]
