"""The agent's world model for shuffled pieces, built from camera frames (the observed model).

After a piece move the belief recognises the frame's cells.  If the result
differs from what the move predicts (a *surprise*), it looks again before
believing it: ``relooks`` more frames are grabbed and each cell takes the
label most frames agree on (ties go to the larger summed probability), so
one bad frame (an occluding hand, a glare) does not send the monitor into
costly replanning.  Touch overrides sight for a cell where a grasp closed
on nothing; that override lasts while the camera keeps seeing the same thing
there, so a systematic misrecognition cannot make the arm grasp at the same
phantom piece again and again.  The arm's position is proprioceptive.
"""

from __future__ import annotations

import logging
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.operators import Action
from nowplan.domains.pieces.board import EMPTY, LABELS, Board, Geometry
from nowplan.domains.pieces.vision import Recognition, Recognizer
from nowplan.worlds.base import Observation

log = logging.getLogger(__name__)

Relook = Callable[[], tuple[int, np.ndarray]]
LookHook = Callable[[dict[str, Any]], None]


@dataclass
class PerceptionLog:
    looks: int = 0  # frames recognised
    relooks: int = 0  # frames grabbed because of a surprise
    surprises_seen: int = 0  # updates whose first frame disagreed with the prediction
    cleared_by_relook: int = 0  # ... and whose re-looks agreed with the prediction after all
    touch_overrides: int = 0
    frames: list[tuple[int, dict[str, str]]] = field(default_factory=list)  # every frame's labels
    updates: list[tuple[int, dict[str, str]]] = field(default_factory=list)  # last frame, believed labels


class PiecesBelief(SymbolicBelief):
    def __init__(self, board: Board, recognizer: Recognizer, relook: Relook | None = None,
                 relooks: int = 2, on_look: LookHook | None = None) -> None:
        super().__init__(board.to_state())
        self.geometry: Geometry = board.geometry
        self.recognizer = recognizer
        self.relook = relook
        self.relooks = relooks
        self.on_look = on_look
        self.log = PerceptionLog()
        self._phantoms: dict[str, str] = {}

    @property
    def board(self) -> Board:
        return Board.from_state(self.geometry, self.state)

    def update(self, action: Action, observation: Observation) -> None:
        data = observation.data if isinstance(observation.data, dict) else {}
        before = self.board
        predicted = before
        if observation.success:
            predicted = Board.from_state(self.geometry, self.state.apply(action.effects()))
        arm = str(data.get("arm", predicted.arm))
        image = data.get("image")
        if image is None:  # an arm move: nothing seen, the prediction stands
            self.state = predicted.with_arm(arm).to_state()
            return
        frames: list[tuple[int, Recognition]] = [(int(data.get("frame", 0)), self._see(image))]
        expected = predicted.labels()
        labels = frames[0][1].labels
        if labels != expected:
            self.log.surprises_seen += 1
            if self.relook is not None:
                for _ in range(self.relooks):
                    fid, img = self.relook()
                    frames.append((fid, self._see(img)))
                    self.log.relooks += 1
                labels = vote([r for _, r in frames])
                if labels == expected:
                    self.log.cleared_by_relook += 1
        if observation.info.get("grasp") == "empty":
            src = str(action.args[1])
            if labels.get(src, EMPTY) != EMPTY:
                self._phantoms[src] = labels[src]
        labels = self._apply_touch(labels)
        for fid, rec in frames:
            self.log.frames.append((fid, rec.labels))
        self.log.updates.append((frames[-1][0], labels))
        believed = Board.of(self.geometry, {c: k for c, k in labels.items() if k != EMPTY}, arm)
        self.state = believed.to_state()
        if self.on_look is not None:
            self.on_look({"action": action, "observation": observation, "frames": frames,
                          "labels": labels, "expected": expected, "board": believed})

    def reobserve(self) -> None:
        """Look afresh, without a prediction: ``1 + relooks`` frames, each cell by majority."""
        if self.relook is None:
            return
        frames = []
        for _ in range(1 + self.relooks):
            fid, img = self.relook()
            frames.append((fid, self._see(img)))
            self.log.relooks += 1
        labels = self._apply_touch(vote([r for _, r in frames]))
        for fid, rec in frames:
            self.log.frames.append((fid, rec.labels))
        self.log.updates.append((frames[-1][0], labels))
        arm = self.board.arm
        self.state = Board.of(self.geometry, {c: k for c, k in labels.items() if k != EMPTY}, arm).to_state()

    def _see(self, image: np.ndarray) -> Recognition:
        self.log.looks += 1
        return self.recognizer.recognize(image, self.geometry)

    def _apply_touch(self, labels: dict[str, str]) -> dict[str, str]:
        out = dict(labels)
        for cell, seen in list(self._phantoms.items()):
            if out.get(cell) == seen:
                out[cell] = EMPTY
                self.log.touch_overrides += 1
            else:
                del self._phantoms[cell]  # the camera changed its mind: trust it again
        return out


def vote(frames: list[Recognition]) -> dict[str, str]:
    """Per cell, the label most frames give; ties go to the larger summed probability."""
    out: dict[str, str] = {}
    for cell in frames[0].labels:
        counts = Counter(r.labels[cell] for r in frames)
        top = max(counts.values())
        tied = [lab for lab, n in counts.items() if n == top]
        if len(tied) == 1 or not frames[0].probabilities:
            out[cell] = tied[0]
            continue
        total = np.sum([r.probabilities[cell] for r in frames], axis=0)
        out[cell] = max(tied, key=lambda lab: float(total[LABELS.index(lab)]))
    return out
