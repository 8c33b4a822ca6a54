"""What the shuffled-pieces domain gives the monitor (pieces.model puts them in DOMAIN.monitor): a model distance and arm adaptation."""

from __future__ import annotations

from collections.abc import Sequence

from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.domains.pieces.meansends import arm_move


def model_distance(a: State, b: State) -> float:
    """Cells whose labels differ between two world models (the arm is not part of a model)."""
    pa = {args[0]: args[1] for args in a.facts("has")}
    pb = {args[0]: args[1] for args in b.facts("has")}
    return float(sum(1 for c in pa.keys() | pb.keys() if pa.get(c) != pb.get(c)))


def start_arm_from_here(actions: Sequence[Action], state: State) -> list[Action]:
    """Re-route the arm: it goes from where it is to each piece it must take (low-level behaviour).

    The stored or continued plan's own ``move_arm`` steps assumed the arm
    elsewhere; they are dropped and one arm move is put before each piece move
    whose source is not where the arm will be.
    """
    arms = state.facts("arm_at")
    arm = str(arms[0][0]) if arms else None
    out: list[Action] = []
    for act in actions:
        if act.name == "move_arm":
            continue
        src = str(act.args[1])
        if arm is not None and arm != src:
            out.append(arm_move(arm, src))
        out.append(act)
        arm = str(act.args[2])
    return out
