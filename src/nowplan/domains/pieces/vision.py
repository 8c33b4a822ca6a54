"""Segment a camera frame into cells and recognise each cell's label (seed 003's NN step).

Segmentation finds the board on the green table from the colour profile of
the image (the camera is calibrated: cells are :data:`CELL` pixels; only the
board's offset, from camera shake, is searched).  Each cell becomes a small
grey patch, normalised for lighting; a scikit-learn multi-layer perceptron
trained at start-up on synthetic frames from the same camera model labels
it ``empty`` or one of the six kinds.  Training is seeded and takes a few
seconds; its accuracy on held-out frames is reported with the recogniser.
"""

from __future__ import annotations

import logging
import random
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Any

import numpy as np

from nowplan.domains.pieces.board import KINDS, LABELS, Board, Geometry, cell_name
from nowplan.domains.pieces.render import CELL, MARGIN, Camera, CameraNoise
from nowplan.errors import require

log = logging.getLogger(__name__)

INSET = 2  # pixels dropped at each cell border
POOL = 2  # average-pooling factor: (CELL - 2*INSET) / POOL pixels per side
SIDE = (CELL - 2 * INSET) // POOL


def _grey(image: np.ndarray) -> np.ndarray:
    rgb = image.astype(np.float32)
    grey: np.ndarray = rgb[..., 0] * 0.299 + rgb[..., 1] * 0.587 + rgb[..., 2] * 0.114
    return grey


def board_origin(image: np.ndarray, geometry: Geometry, shake: int = 3) -> tuple[int, int]:
    """Pixel (x, y) of the board's first cell: where the board's colour starts on the table."""
    rgb = image.astype(np.float32)
    boardish = (rgb[..., 0] - rgb[..., 1]) > 0.0  # the table is green, squares and frame are not
    nominal = MARGIN + 3
    lo, hi = nominal - shake - 3, nominal + shake + 3
    width, height = geometry.cols * CELL, geometry.rows * CELL

    def best(profile_fn: Any, extent: int) -> int:
        scores = []
        for o in range(lo, hi + 1):
            inside = profile_fn(o, o + extent)
            outside = profile_fn(o - 4, o - 2)  # just before the frame: table
            scores.append((inside - outside, -abs(o - nominal), o))
        return max(scores)[2]

    col_frac = boardish.mean(axis=0)
    row_frac = boardish[:, : nominal + width].mean(axis=1)
    x0 = best(lambda a, b: float(col_frac[max(a, 0):b].mean()) if b > max(a, 0) else 0.0, width)
    y0 = best(lambda a, b: float(row_frac[max(a, 0):b].mean()) if b > max(a, 0) else 0.0, height)
    return x0, y0


def segment(image: np.ndarray, geometry: Geometry) -> tuple[list[str], np.ndarray]:
    """Cells (board then tray) and their feature vectors, one row per cell."""
    grey = _grey(image)
    x0, y0 = board_origin(image, geometry)
    cells: list[str] = []
    patches: list[np.ndarray] = []
    for r in range(geometry.rows):
        for c in [*range(geometry.cols), geometry.tray_col]:
            xa, ya = x0 + c * CELL + INSET, y0 + r * CELL + INSET
            patch = grey[ya: ya + SIDE * POOL, xa: xa + SIDE * POOL]
            if patch.shape != (SIDE * POOL, SIDE * POOL):  # the board runs off the frame
                padded = np.full((SIDE * POOL, SIDE * POOL), float(grey.mean()), dtype=np.float32)
                padded[: patch.shape[0], : patch.shape[1]] = patch
                patch = padded
            cells.append(cell_name(r, c))
            patches.append(patch)
    stack = np.stack(patches)
    scale = float(np.median(stack)) + 1.0  # the frame's lighting
    return cells, _features(stack, scale)


def _features(patches: np.ndarray, scale: float) -> np.ndarray:
    n = patches.shape[0]
    pooled = patches.reshape(n, SIDE, POOL, SIDE, POOL).mean(axis=(2, 4)).reshape(n, -1)
    mean = pooled.mean(axis=1, keepdims=True)
    std = pooled.std(axis=1, keepdims=True)
    shape = (pooled - mean) / np.maximum(std, 0.05 * scale)
    extra = np.hstack([std / scale, mean / scale])
    return np.hstack([shape, extra]).astype(np.float32)


@dataclass(frozen=True)
class Recognition:
    labels: dict[str, str]
    confidence: dict[str, float]
    probabilities: dict[str, np.ndarray] = field(default_factory=dict, compare=False, repr=False)


@dataclass(frozen=True)
class Recognizer:
    """A trained cell classifier with its held-out accuracy."""

    model: Any = field(compare=False, repr=False)
    seed: int
    accuracy: float  # fraction of held-out cells labelled correctly
    piece_accuracy: float  # the same over occupied cells only
    samples: int
    train_s: float

    def recognize(self, image: np.ndarray, geometry: Geometry) -> Recognition:
        cells, x = segment(image, geometry)
        with _one_thread():
            proba = self.model.predict_proba(x)
        classes = list(self.model.classes_)
        idx = proba.argmax(axis=1)
        labels = {c: LABELS[int(classes[i])] for c, i in zip(cells, idx, strict=True)}
        conf = {c: float(p[i]) for c, p, i in zip(cells, proba, idx, strict=True)}
        full = {}
        for c, p in zip(cells, proba, strict=True):
            v = np.zeros(len(LABELS))
            v[[int(k) for k in classes]] = p
            full[c] = v
        return Recognition(labels, conf, full)

    def summary(self) -> str:
        return (f"cell classifier: MLP trained on {self.samples} synthetic cells in {self.train_s:.1f} s, "
                f"held-out accuracy {100 * self.accuracy:.2f}% (pieces {100 * self.piece_accuracy:.2f}%)")


def _one_thread() -> Any:
    """Small matrices: one BLAS thread is much faster than several fighting over the cores."""
    limits = require("threadpoolctl", "vision")
    return limits.threadpool_limits(limits=1)


def _random_board(geometry: Geometry, rng: random.Random, density: float) -> Board:
    cells = list(geometry.cells)
    occupied = [c for c in cells if rng.random() < density]
    return Board.of(geometry, {c: rng.choice(KINDS) for c in occupied}, cells[0])


def synthetic_cells(
    frames: int, seed: int, noise: CameraNoise | None = None, geometry: Geometry | None = None,
    density: float = 0.55,
) -> tuple[np.ndarray, np.ndarray]:
    """Features and label indices of every cell of ``frames`` random noisy frames."""
    geometry = geometry or Geometry(6, 6)
    rng = random.Random(seed)
    camera = Camera(geometry, seed=rng.randrange(2**31), noise=noise)
    xs: list[np.ndarray] = []
    ys: list[int] = []
    for _ in range(frames):
        board = _random_board(geometry, rng, density)
        cells, x = segment(camera.grab(board), geometry)
        xs.append(x)
        ys.extend(LABELS.index(board.at(c) or "empty") for c in cells)
    return np.vstack(xs), np.asarray(ys)


def train_recognizer(
    seed: int = 0, frames: int = 200, heldout_frames: int = 50, noise: CameraNoise | None = None,
    hidden: tuple[int, ...] = (96,),
) -> Recognizer:
    """Train the cell classifier on synthetic frames and measure it on held-out ones.

    The held-out frames come from another seed stream of the same camera model.
    """
    nn = require("sklearn.neural_network", "vision")
    t0 = time.perf_counter()
    x, y = synthetic_cells(frames, seed, noise)
    model = nn.MLPClassifier(hidden_layer_sizes=hidden, alpha=1e-3, max_iter=200, random_state=seed,
                             tol=1e-4, n_iter_no_change=10)
    with _one_thread():
        model.fit(x, y)
    train_s = time.perf_counter() - t0
    xh, yh = synthetic_cells(heldout_frames, seed + 7919, noise)
    with _one_thread():
        pred = model.predict(xh)
    acc = float((pred == yh).mean())
    occ = yh != 0
    piece_acc = float((pred[occ] == yh[occ]).mean()) if occ.any() else 1.0
    rec = Recognizer(model, seed, acc, piece_acc, int(len(y)), train_s)
    log.info("%s", rec.summary())
    return rec


@lru_cache(maxsize=8)
def recognizer(seed: int = 0) -> Recognizer:
    """The start-up recogniser for ``seed``, trained once per process."""
    return train_recognizer(seed)


def misrecognised(recognized: Mapping[str, str], truth: Board) -> list[str]:
    """Cells whose recognised label differs from the true one."""
    return sorted(c for c, lab in recognized.items() if (truth.at(c) or "empty") != lab)
