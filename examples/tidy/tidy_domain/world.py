"""The true house (a gripper that drops what it carries, a cat that moves things) and what the
robot sees: its own room only."""

from __future__ import annotations

import random
from dataclasses import dataclass

from nowplan.api import Action, Atom, Domain, State, SymbolicWorld, atom

from tidy_domain.model import FLOOR


@dataclass(frozen=True)
class Seen:
    """What the robot sees after an action: its room, what it holds, the doors of its room
    (door, open, unlocked) and the things in its room with what each lies on."""

    room: str
    holding: str | None
    doors: tuple[tuple[str, bool, bool], ...]
    things: tuple[tuple[str, str], ...]


def room_of(state: State) -> str:
    return str(state.facts("robot_in")[0][0])


def free_floor(state: State, room: str) -> list[str]:
    clear = {str(x) for (x,) in state.facts("clear")}
    return sorted(str(s) for (s, rm) in state.facts("in") if str(rm) == room and str(s).startswith(FLOOR)
                  and str(s) in clear)


def relocate(state: State, thing: str, spot: str, room: str) -> list[Atom]:
    """The atoms that move a clear (or held) ``thing`` onto the free floor ``spot`` of ``room``."""
    out: list[Atom] = []
    for (x, below) in state.facts("on"):
        if str(x) == thing:
            out += [atom("on", thing, below, value=False), atom("clear", below)]
    for (x, rm) in state.facts("in"):
        if str(x) == thing:
            out.append(atom("in", thing, rm, value=False))
    if state.holds(atom("holding", thing)):
        out += [atom("holding", thing, value=False), atom("hand_empty")]
    return out + [atom("on", thing, spot), atom("in", thing, room), atom("clear", spot, value=False)]


def cat(state: State, rng: random.Random) -> list[Atom]:
    """Exogenous change: the cat drags a clear thing that is not a key to a free floor spot of its
    room or of a room next to it (doors do not stop the cat)."""
    clear = {str(x) for (x,) in state.facts("clear")}
    keys = {str(x) for (x, _) in state.facts("opens")}
    loose = sorted((str(x), str(rm)) for (x, rm) in state.facts("in")
                   if str(x) in clear and any(str(y) == str(x) for (y, _) in state.facts("on")) and str(x) not in keys)
    if not loose:
        return []
    thing, room = rng.choice(loose)
    near = sorted({str(b) for (_, a, b) in state.facts("connects") if str(a) == room} | {room})
    dest = rng.choice(near)
    spots = free_floor(state, dest)
    return relocate(state, thing, rng.choice(spots), dest) if spots else []


class TidyWorld(SymbolicWorld):
    """A symbolic house whose gripper drops what it carries on a move with probability ``drop``
    (the thing lands on a free floor spot of the room arrived in), whose cat moves things
    (``exogenous_prob``), and which shows the robot only its own room."""

    def __init__(self, domain: Domain, state: State, *, seed: int = 0, failure_prob: float = 0.0,
                 exogenous_prob: float = 0.0, drop: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=cat,
                         exogenous_prob=exogenous_prob)
        self.drop = drop

    def apply(self, action: Action) -> None:
        super().apply(action)
        held = [str(x) for (x,) in self.state.facts("holding")]
        if action.name == "move" and held and self.rng.random() < self.drop:
            room = room_of(self.state)
            spots = free_floor(self.state, room)
            if spots:
                self.state = self.state.apply(relocate(self.state, held[0], spots[0], room))

    def observe(self, action: Action, success: bool) -> Seen:
        s = self.state
        room = room_of(s)
        held = [str(x) for (x,) in s.facts("holding")]
        doors = sorted({str(dr) for (dr, a, _) in s.facts("connects") if str(a) == room})
        ons = {str(x): str(y) for (x, y) in s.facts("on")}
        things = tuple(sorted((str(x), ons[str(x)]) for (x, rm) in s.facts("in") if str(rm) == room and str(x) in ons))
        return Seen(room, held[0] if held else None,
                    tuple((dr, s.holds(atom("open", dr)), s.holds(atom("unlocked", dr))) for dr in doors), things)


__all__ = ["Seen", "TidyWorld", "cat", "free_floor", "relocate", "room_of"]
