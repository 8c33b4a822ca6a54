"""The simulated shuffled-pieces world: a true board, a robot arm, a camera and a person.

The world keeps its own true :class:`~nowplan.domains.pieces.board.Board`;
the agent only gets observations: the arm's position (proprioception), whether
a grasp or a placement worked (touch), and after every piece move a camera
frame.  The arm executes physically: ``move_piece(k, a, b)`` travels to ``a``
if it is not there, grasps whatever stands there (failing on an empty cell)
and places it on ``b`` (failing if ``b`` is occupied).  Between steps a
person may, with a seeded probability, move a piece, remove one (to the
tray beside the board) or add a new one.
"""

from __future__ import annotations

import logging
import random
from dataclasses import dataclass

import numpy as np

from nowplan.core.operators import Action
from nowplan.core.state import State
from nowplan.domains.pieces.board import KINDS, Board, distance
from nowplan.domains.pieces.render import Camera
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class Disturbances:
    """How often and how a person disturbs the board (after each piece move)."""

    prob: float = 0.0
    move: float = 0.6
    remove: float = 0.2
    add: float = 0.2

    def __post_init__(self) -> None:
        if not 0.0 <= self.prob <= 1.0:
            raise ValueError("disturbance probability must be in [0, 1]")


class PiecesWorld:
    def __init__(self, board: Board, camera: Camera, *, seed: int = 0,
                 disturbances: Disturbances | None = None) -> None:
        self.board = board
        self.camera = camera
        self.rng = random.Random(seed)
        self.disturbances = disturbances or Disturbances()
        self.travel = 0.0  # the arm's true travel
        self.piece_moves = 0
        self.failures = 0
        self.exogenous_events = 0
        self.truth: dict[int, dict[str, str]] = {}  # frame id -> true labels (for evaluation only)
        self._frame = 0

    @property
    def state(self) -> State:
        return self.board.to_state()

    def set_faults(self, *, failure_prob: float | None = None, exogenous_prob: float | None = None) -> None:
        """``nowplan run --exogenous-prob`` (disturbances); failures of the arm are not simulated."""
        if failure_prob:
            raise ValueError("the pieces world does not inject arm failures; use --exogenous-prob (disturbances)")
        if exogenous_prob is not None:
            self.exogenous_prob = exogenous_prob

    def true_state(self) -> State:
        """The board as it is (success is judged on it at the end of a run)."""
        return self.state

    @property
    def exogenous_prob(self) -> float:
        return self.disturbances.prob

    @exogenous_prob.setter
    def exogenous_prob(self, p: float) -> None:
        d = self.disturbances
        self.disturbances = Disturbances(p, d.move, d.remove, d.add)

    # -- acting --------------------------------------------------------------------
    def _go(self, cell: str) -> None:
        self.travel += distance(self.board.arm, cell)
        self.board = self.board.with_arm(cell)

    def execute(self, action: Action) -> Observation:
        info: dict[str, object] = {}
        if action.name == "move_arm":
            self._go(str(action.args[1]))
            return Observation(True, {"arm": self.board.arm}, (), info)
        if action.name != "move_piece":
            return Observation(False, {"arm": self.board.arm}, (), {"reason": f"unknown action {action.name}"})
        _kind, src, dst = (str(x) for x in action.args)
        self._go(src)
        ok = True
        if self.board.at(src) is None:
            ok, info["reason"], info["grasp"] = False, f"nothing to grasp at {src}", "empty"
        elif self.board.at(dst) is not None:
            ok, info["reason"], info["place"] = False, f"cannot place: {dst} is occupied", "blocked"
        else:
            self.travel += distance(src, dst)
            self.board = self.board.move(src, dst)
            self.piece_moves += 1
        if not ok:
            self.failures += 1
        changes = self._disturb()
        fid, image = self.look()
        info["frame"] = fid
        return Observation(ok, {"arm": self.board.arm, "image": image, "frame": fid}, changes, info)

    def look(self) -> tuple[int, np.ndarray]:
        """Grab a camera frame of the board as it is now (the agent's re-look)."""
        self._frame += 1
        self.truth[self._frame] = self.board.labels()
        return self._frame, self.camera.grab(self.board)

    # -- the person ----------------------------------------------------------------------
    def _disturb(self) -> tuple[str, ...]:
        d = self.disturbances
        if d.prob <= 0 or self.rng.random() >= d.prob:
            return ()
        total = d.move + d.remove + d.add
        x = self.rng.random() * total
        kind = "move" if x < d.move else ("remove" if x < d.move + d.remove else "add")
        b = self.board
        free = [c for c in b.empty_cells() if c != b.arm]
        pieces = [c for c, _ in b if b.geometry.on_board(c) and c != b.arm]
        slots = [c for c in b.geometry.tray_cells if b.at(c) is None]
        if kind == "remove" and (not pieces or not slots):
            kind = "move"
        if kind == "add" and len(free) < 2:
            kind = "move"
        if kind == "move" and (not pieces or not free):
            return ()
        if kind == "add":
            cell, new = self.rng.choice(free), self.rng.choice(KINDS)
            self.board = Board.of(b.geometry, {**b.placement(), cell: new}, b.arm)
            text = f"a person added a {new} on {cell}"
        else:
            src = self.rng.choice(pieces)
            dst = slots[0] if kind == "remove" else self.rng.choice(free)
            what = b.at(src)
            self.board = b.move(src, dst).with_arm(b.arm)
            text = (f"a person removed the {what} from {src} (to the tray, {dst})" if kind == "remove"
                    else f"a person moved the {what} from {src} to {dst}")
        self.exogenous_events += 1
        log.debug("%s", text)
        return (text,)
