"""The simulated warehouse: the true stacks, a barcode scanner that misses and misreads,
workers who move boxes between shelves, and a fragile box whose pick may fail."""

from __future__ import annotations

import random
from collections.abc import Mapping, Sequence

from nowplan.api import Action, Atom, Domain, State, SymbolicWorld, atom

# what the robot reports after each action: where it is, its battery, what it holds, and for
# each slot at its location the labels the scanner read, bottom to top (None: the slot's scan
# missed; the belief keeps what it thought was there)
Scan = dict[str, object]


def stacks(state: State, slots: Sequence[str]) -> dict[str, list[str]]:
    """Each slot's stack, bottom to top, read off ``on`` facts."""
    above = {str(x): str(b) for b, x in state.facts("on")}
    out: dict[str, list[str]] = {}
    for s in slots:
        col: list[str] = []
        cur = s
        while cur in above:
            cur = above[cur]
            col.append(cur)
        out[s] = col
    return out


def stack_atoms(col_from: list[str], slot_from: str, slot_to: str, col_to: list[str], box: str) -> list[Atom]:
    """The atoms of moving the top ``box`` of one stack onto the top of another."""
    below = col_from[-2] if len(col_from) > 1 else slot_from
    onto = col_to[-1] if col_to else slot_to
    return [atom("on", box, below, value=False), atom("clear", below), atom("in_slot", box, slot_from, value=False),
            atom("on", box, onto), atom("clear", onto, value=False), atom("in_slot", box, slot_to)]


class WarehouseWorld(SymbolicWorld):
    """The true warehouse.  ``miss``: a slot's scan reads nothing; ``false_pos``: one label of a
    scanned stack is read as another box's; ``fragile``: a pick of a fragile box fails;
    ``exogenous_prob``: a worker moves a top box to another shelf slot (never the packing slot)."""

    def __init__(self, domain: Domain, state: State, *, slots_at: Mapping[str, Sequence[str]],
                 protected: Sequence[str], boxes: Sequence[str], fragile_boxes: Sequence[str] = (), seed: int = 0,
                 failure_prob: float = 0.0, exogenous_prob: float = 0.0, miss: float = 0.0, false_pos: float = 0.0,
                 fragile: float = 0.0) -> None:
        super().__init__(domain, state, seed=seed, failure_prob=failure_prob, exogenous=self.worker,
                         exogenous_prob=exogenous_prob)
        self.slots_at = {k: list(v) for k, v in slots_at.items()}
        self.all_slots = [s for v in self.slots_at.values() for s in v]
        self.protected = set(protected)
        self.boxes = list(boxes)
        self.fragile_boxes = set(fragile_boxes)
        self.miss, self.false_pos, self.fragile = miss, false_pos, fragile

    def worker(self, state: State, rng: random.Random) -> list[Atom]:
        """A worker takes the top box of one shelf stack to the top of another (not the packing slot)."""
        cols = stacks(state, self.all_slots)
        free = [s for s in self.all_slots if s not in self.protected]
        sources = [s for s in free if cols[s]]
        if not sources:
            return []
        src = rng.choice(sources)
        dst = rng.choice([s for s in free if s != src and len(cols[s]) < 3] or [src])
        if dst == src:
            return []
        return stack_atoms(cols[src], src, dst, cols[dst], cols[src][-1])

    def fault(self, action: Action) -> str | None:
        if (action.name in ("pick", "unstack") and str(action.args[0]) in self.fragile_boxes
                and self.rng.random() < self.fragile):
            return f"fragile box {action.args[0]} slipped from the suction cup"
        return None

    def observe(self, action: Action, success: bool) -> Scan:
        st = self.state
        (loc,) = st.facts("robot_at")[0]
        (level,) = st.facts("batt")[0]
        held = [str(x) for (x,) in st.facts("holding")]
        seen: dict[str, list[str] | None] = {}
        for s, col in stacks(st, self.slots_at.get(str(loc), [])).items():
            if self.rng.random() < self.miss:
                seen[s] = None
                continue
            read = list(col)
            if read and self.rng.random() < self.false_pos:  # one label misread as another box's
                i = self.rng.randrange(len(read))
                read[i] = self.rng.choice([x for x in self.boxes if x != read[i]])
            seen[s] = read
        return {"robot_at": str(loc), "batt": str(level), "holding": held[0] if held else None, "slots": seen}
