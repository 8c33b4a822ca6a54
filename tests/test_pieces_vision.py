"""The camera loop: segmentation, the start-up classifier, re-looking before believing a surprise."""

from __future__ import annotations

import random

import numpy as np
import pytest

pytest.importorskip("sklearn")
pytest.importorskip("PIL")

from nowplan.core.operators import Action  # noqa: E402
from nowplan.domains.pieces.belief import PiecesBelief, vote  # noqa: E402
from nowplan.domains.pieces.board import KINDS, LABELS, Board, Geometry  # noqa: E402
from nowplan.domains.pieces.meansends import piece_move  # noqa: E402
from nowplan.domains.pieces.render import Camera, CameraNoise  # noqa: E402
from nowplan.domains.pieces.vision import (  # noqa: E402
    Recognition,
    Recognizer,
    misrecognised,
    recognizer,
    synthetic_cells,
)
from nowplan.domains.pieces.world import PiecesWorld  # noqa: E402

G = Geometry(8, 8)
QUIET = CameraNoise(jitter=0.0, rotation_deg=0.0, scale=(1.0, 1.0), brightness=(1.0, 1.0), gradient=0.0,
                    pixel_sigma=(0.0, 0.0), occlusion_prob=0.0, shake=0)


@pytest.fixture(scope="module")
def rec() -> Recognizer:
    return recognizer(0)


def _board(seed: int, n: int = 14) -> Board:
    rng = random.Random(seed)
    return Board.of(G, {c: rng.choice(KINDS) for c in rng.sample(list(G.cells), n)}, "r0c0")


def test_classifier_is_accurate_on_held_out_synthetic_images(rec: Recognizer) -> None:
    assert rec.accuracy >= 0.98 and rec.samples > 1000
    x, y = synthetic_cells(20, seed=424242)  # frames neither training nor the stored figure used
    from threadpoolctl import threadpool_limits

    with threadpool_limits(1):
        pred = rec.model.predict(x)
    assert float((pred == y).mean()) >= 0.98
    assert set(np.unique(y)) == set(range(len(LABELS)))  # every class was tested


def test_clean_frames_are_read_exactly(rec: Recognizer) -> None:
    cam = Camera(G, seed=3, noise=QUIET)
    for seed in range(3):
        b = _board(seed)
        assert misrecognised(rec.recognize(cam.grab(b), G).labels, b) == []


def test_segmentation_follows_camera_shake(rec: Recognizer) -> None:
    noise = CameraNoise(occlusion_prob=0.0, shake=3, pixel_sigma=(2.0, 4.0))
    cam = Camera(G, seed=8, noise=noise)
    errors = sum(len(misrecognised(rec.recognize(cam.grab(b), G).labels, b))
                 for b in (_board(10 + s) for s in range(8)))
    assert errors <= 2  # of 8 × 72 cells, with the board shifted by up to 3 px each frame


def _recognition(labels: dict[str, str], p: float) -> Recognition:
    probs = {}
    for c, lab in labels.items():
        v = np.full(len(LABELS), (1 - p) / (len(LABELS) - 1))
        v[LABELS.index(lab)] = p
        probs[c] = v
    return Recognition(dict(labels), {c: p for c in labels}, probs)


def test_vote_outvotes_one_bad_frame() -> None:
    good = {"r0c0": "pawn", "r0c1": "empty"}
    bad = {"r0c0": "queen", "r0c1": "rook"}
    out = vote([_recognition(bad, 0.99), _recognition(good, 0.6), _recognition(good, 0.6)])
    assert out == good


class _GlitchOnce:
    """A recogniser whose n-th frame reads one cell wrong (a hand over it, say)."""

    def __init__(self, inner: Recognizer, bad_call: int, cell: str) -> None:
        self.inner, self.bad_call, self.cell, self.calls = inner, bad_call, cell, 0

    def recognize(self, image: np.ndarray, geometry: Geometry) -> Recognition:
        self.calls += 1
        r = self.inner.recognize(image, geometry)
        if self.calls != self.bad_call:
            return r
        labels = dict(r.labels)
        labels[self.cell] = "king" if labels[self.cell] != "king" else "pawn"
        return Recognition(labels, r.confidence, r.probabilities)


def _move(board: Board) -> tuple[Action, Board]:
    src, kind = board.pieces[0]
    dst = next(c for c in board.empty_cells() if c != src)
    return piece_move(kind, src, dst), board.move(src, dst)


def test_one_bad_frame_is_cleared_by_relooking(rec: Recognizer) -> None:
    board = _board(1)
    world = PiecesWorld(board.with_arm(board.pieces[0][0]), Camera(G, seed=2, noise=QUIET), seed=0)
    glitch = _GlitchOnce(rec, 1, next(c for c in G.board_cells if board.at(c) is None))
    belief = PiecesBelief(world.board, glitch, relook=world.look, relooks=2)  # type: ignore[arg-type]
    action, after = _move(world.board)
    obs = world.execute(action)
    belief.update(action, obs)
    assert belief.board.placement() == after.placement()
    assert belief.log.relooks == 2 and belief.log.cleared_by_relook == 1


def test_without_relooks_the_bad_frame_is_believed(rec: Recognizer) -> None:
    board = _board(1)
    world = PiecesWorld(board.with_arm(board.pieces[0][0]), Camera(G, seed=2, noise=QUIET), seed=0)
    cell = next(c for c in G.board_cells if board.at(c) is None)
    belief = PiecesBelief(world.board, _GlitchOnce(rec, 1, cell), relook=world.look,  # type: ignore[arg-type]
                          relooks=0)
    action, after = _move(world.board)
    belief.update(action, world.execute(action))
    assert belief.board.placement() != after.placement() and belief.board.at(cell) is not None
