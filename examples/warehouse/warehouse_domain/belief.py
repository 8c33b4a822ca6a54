"""What the robot believes: a point belief built from its manifest and its scans.

The robot sees only the slots at its own location, through a scanner that may miss a slot
(the belief keeps what it thought was there) or misread a label.  A box the belief can no
longer place (it was believed in a slot just scanned, and is not there) is guessed on top of a
stack at the location the robot saw longest ago: the robot searches the warehouse by going
where its knowledge is oldest.

A scan that contradicts what the robot expects (its own action's effects applied to what it
believed) is believed only when the next scan of that slot reads the same: a misread label
(a false positive) is seldom repeated.  A first version adopted every read at once; a box put
aside on the packing slot and misread as an ordered box then ended runs "reached" in the belief
while the world disagreed (benchmarks/results/heldout9/README.md).
"""

from __future__ import annotations

from collections.abc import Hashable, Mapping, Sequence

from nowplan.api import Action, Atom, Observation, State, SymbolicBelief, atom

from warehouse_domain.world import stacks


def arrangement_atoms(cols: Mapping[str, list[str]]) -> list[Atom]:
    """``on``, ``in_slot`` and ``clear`` facts of stacks (bottom to top)."""
    out: list[Atom] = []
    for s, col in cols.items():
        below = s
        for box in col:
            out += [atom("on", box, below), atom("in_slot", box, s)]
            below = box
        out.append(atom("clear", below))
    return out


class WarehouseBelief(SymbolicBelief):
    """A point belief: the manifest, overwritten by what the scanner reads."""

    def __init__(self, state: State, *, slots_at: Mapping[str, Sequence[str]], statics: Sequence[Atom],
                 boxes: Sequence[str]) -> None:
        super().__init__(state)
        self.slots_at = {k: list(v) for k, v in slots_at.items()}
        self.all_slots = [s for v in self.slots_at.values() for s in v]
        self.statics = list(statics)
        self.boxes = list(boxes)
        self.step = 0
        self.seen_at: dict[str, int] = {loc: -1 for loc in self.slots_at}
        self.pending: dict[str, tuple[str, ...]] = {}  # slot: a surprising read, not yet confirmed

    def fingerprint(self) -> Hashable:
        """The believed state, which locations were seen longest ago (the search's memory) and the
        reads awaiting confirmation."""
        return (self.state, tuple(sorted(self.seen_at, key=lambda k: (self.seen_at[k], k))),
                tuple(sorted(self.pending.items())))

    def update(self, action: Action, observation: Observation) -> None:
        data = observation.data
        if not isinstance(data, dict):
            return
        self.step += 1
        loc, held = str(data["robot_at"]), data["holding"]
        expected = self.state.apply(action.effects()) if observation.success else self.state
        cols = stacks(expected, self.all_slots)
        read: dict[str, list[str]] = {}
        for s, labels in dict(data["slots"]).items():
            if labels is None:
                continue  # the scan missed: keep the old belief about this slot
            col: list[str] = []
            for x in labels:
                if x not in col and x != held:
                    col.append(x)
            if col == cols[s]:
                self.pending.pop(s, None)
            elif self.pending.get(s) == tuple(col):  # read the same twice: believe it
                del self.pending[s]
                read[s] = col
            else:
                self.pending[s] = tuple(col)
        self.seen_at[loc] = self.step
        placed = {x for col in read.values() for x in col} | ({held} if held else set())
        new: dict[str, list[str]] = {}
        for s in self.all_slots:
            new[s] = read[s] if s in read else [x for x in cols[s] if x not in placed]
        placed |= {x for col in new.values() for x in col}
        lost = [x for x in self.boxes if x not in placed]
        if lost:  # guess them where the robot's knowledge is oldest (not here)
            others = sorted((k for k in self.slots_at if k != loc and self.slots_at[k]),
                            key=lambda k: (self.seen_at[k], k))
            for x in lost:
                target = others[0] if others else loc
                slot = min(self.slots_at[target], key=lambda z: (len(new[z]), z))
                new[slot].append(x)
        facts = [atom("robot_at", loc), atom("batt", str(data["batt"]))] + arrangement_atoms(new) + self.statics
        facts += [atom("holding", held), atom("clear", held)] if held else [atom("hand_empty")]
        self.state = State(facts)
