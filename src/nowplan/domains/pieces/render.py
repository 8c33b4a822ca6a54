"""Top-view camera images of the board, and a clean board diagram (Pillow + numpy).

The camera draws each piece's glyph with random position, scale and
rotation jitter, then applies a lighting change (overall brightness and a
linear gradient), pixel noise, and, in some frames, a partial occluder (a
hand or a sleeve over a few cells).  The board sits on a green table with a
small random offset (camera shake); the tray is a column one cell to the
right.  Every random choice comes from the camera's seeded generator.
"""

from __future__ import annotations

import math
import random
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from nowplan.domains.pieces.board import KINDS, LETTERS, Board, Geometry, cell_name, cell_rc
from nowplan.errors import require

CELL = 24  # pixels per cell
MARGIN = 10  # table visible around the board
TABLE = (92, 118, 88)
LIGHT = (232, 214, 176)
DARK = (176, 132, 92)
TRAY = (214, 200, 182)
INK = (28, 26, 24)

Pt = tuple[float, float]

# glyphs as polygons in the unit square (y down); ("ellipse", box) for round parts
GLYPHS: dict[str, list[tuple[str, list[Pt]]]] = {
    "pawn": [("ellipse", [(0.38, 0.18), (0.62, 0.42)]),
             ("poly", [(0.4, 0.42), (0.6, 0.42), (0.7, 0.78), (0.3, 0.78)]),
             ("poly", [(0.24, 0.76), (0.76, 0.76), (0.76, 0.86), (0.24, 0.86)])],
    "rook": [("poly", [(0.3, 0.32), (0.7, 0.32), (0.72, 0.84), (0.28, 0.84)]),
             ("poly", [(0.26, 0.14), (0.38, 0.14), (0.38, 0.34), (0.26, 0.34)]),
             ("poly", [(0.44, 0.14), (0.56, 0.14), (0.56, 0.34), (0.44, 0.34)]),
             ("poly", [(0.62, 0.14), (0.74, 0.14), (0.74, 0.34), (0.62, 0.34)])],
    "knight": [("poly", [(0.28, 0.86), (0.34, 0.46), (0.5, 0.14), (0.6, 0.2), (0.8, 0.4),
                         (0.74, 0.5), (0.52, 0.44), (0.7, 0.86)])],
    "bishop": [("ellipse", [(0.34, 0.12), (0.66, 0.7)]),
               ("poly", [(0.26, 0.72), (0.74, 0.72), (0.74, 0.86), (0.26, 0.86)]),
               ("slit", [(0.42, 0.3), (0.6, 0.46)])],
    "queen": [("poly", [(0.24, 0.84), (0.16, 0.22), (0.36, 0.5), (0.5, 0.12), (0.64, 0.5),
                        (0.84, 0.22), (0.76, 0.84)])],
    "king": [("poly", [(0.45, 0.06), (0.55, 0.06), (0.55, 0.36), (0.45, 0.36)]),
             ("poly", [(0.34, 0.14), (0.66, 0.14), (0.66, 0.24), (0.34, 0.24)]),
             ("poly", [(0.3, 0.36), (0.7, 0.36), (0.78, 0.86), (0.22, 0.86)])],
}


@dataclass(frozen=True)
class CameraNoise:
    """How bad the pictures are (pixel values on a 0–255 scale)."""

    jitter: float = 0.07  # glyph offset, fraction of a cell
    scale: tuple[float, float] = (0.85, 1.08)
    rotation_deg: float = 12.0
    brightness: tuple[float, float] = (0.6, 1.3)
    gradient: float = 0.3  # lighting change across the image
    pixel_sigma: tuple[float, float] = (3.0, 12.0)
    occlusion_prob: float = 0.25  # chance that a frame has an occluder
    occluder_cells: tuple[float, float] = (0.5, 1.4)  # occluder size in cells
    shake: int = 3  # pixels of camera shake


def image_size(g: Geometry) -> tuple[int, int]:
    """(width, height) of a camera frame."""
    return ((g.cols + 2) * CELL + 2 * MARGIN + 2 * 3, g.rows * CELL + 2 * MARGIN + 2 * 3)


def _cell_box(r: int, c: int, ox: int, oy: int) -> tuple[int, int, int, int]:
    x0, y0 = ox + c * CELL, oy + r * CELL
    return x0, y0, x0 + CELL, y0 + CELL


def _square_colour(g: Geometry, r: int, c: int) -> tuple[int, int, int]:
    if c == g.tray_col:
        return TRAY
    return LIGHT if (r + c) % 2 == 0 else DARK


def draw_glyph(draw: object, kind: str, box: tuple[int, int, int, int], rng: random.Random | None,
               noise: CameraNoise, ink: tuple[int, int, int] = INK) -> None:
    """Draw ``kind`` inside ``box``, jittered by ``rng`` (None: the canonical glyph)."""
    x0, y0, x1, y1 = box
    size = x1 - x0
    if rng is not None:
        dx, dy = (rng.uniform(-noise.jitter, noise.jitter) for _ in range(2))
        s = rng.uniform(*noise.scale)
        th = math.radians(rng.uniform(-noise.rotation_deg, noise.rotation_deg))
    else:
        dx = dy = th = 0.0
        s = 1.0

    def tf(p: Pt) -> tuple[float, float]:
        u, v = (p[0] - 0.5) * s, (p[1] - 0.5) * s
        u, v = u * math.cos(th) - v * math.sin(th), u * math.sin(th) + v * math.cos(th)
        return (x0 + (u + 0.5 + dx) * size, y0 + (v + 0.5 + dy) * size)

    for shape, pts in GLYPHS[kind]:
        if shape == "ellipse":
            (a, b), (c, d) = tf(pts[0]), tf(pts[1])
            draw.ellipse([min(a, c), min(b, d), max(a, c), max(b, d)], fill=ink)  # type: ignore[attr-defined]
        elif shape == "slit":
            draw.line([tf(pts[0]), tf(pts[1])], fill=(240, 236, 220), width=max(1, size // 12))  # type: ignore[attr-defined]
        else:
            draw.polygon([tf(p) for p in pts], fill=ink)  # type: ignore[attr-defined]


class Camera:
    """Grabs noisy top-view frames of a board; seeded."""

    def __init__(self, geometry: Geometry, seed: int = 0, noise: CameraNoise | None = None) -> None:
        self.geometry = geometry
        self.rng = random.Random(seed)
        self.noise = noise or CameraNoise()
        self.frames = 0

    def grab(self, board: Board | Mapping[str, str]) -> np.ndarray:
        """An RGB ``uint8`` frame (height × width × 3) of the placement."""
        image_mod = require("PIL.Image", "vision")
        draw_mod = require("PIL.ImageDraw", "vision")
        g, n, rng = self.geometry, self.noise, self.rng
        placement = board.placement() if isinstance(board, Board) else dict(board)
        w, h = image_size(g)
        img = image_mod.new("RGB", (w, h), TABLE)
        draw = draw_mod.Draw(img)
        ox = MARGIN + 3 + rng.randint(-n.shake, n.shake)
        oy = MARGIN + 3 + rng.randint(-n.shake, n.shake)
        frame_box = [ox - 2, oy - 2, ox + g.cols * CELL + 1, oy + g.rows * CELL + 1]
        draw.rectangle(frame_box, outline=(60, 40, 30), width=2)
        for r in range(g.rows):
            for c in [*range(g.cols), g.tray_col]:
                box = _cell_box(r, c, ox, oy)
                draw.rectangle([box[0], box[1], box[2] - 1, box[3] - 1], fill=_square_colour(g, r, c))
                kind = placement.get(cell_name(r, c))
                if kind is not None:
                    shade = rng.randint(-10, 18)
                    draw_glyph(draw, kind, box, rng, n, tuple(max(0, v + shade) for v in INK))  # type: ignore[arg-type]
        if rng.random() < n.occlusion_prob:
            self._occlude(draw, w, h, ox, oy)
        arr = np.asarray(img, dtype=np.float32)
        arr = self._light(arr)
        self.frames += 1
        return np.clip(arr, 0, 255).astype(np.uint8)

    def _occlude(self, draw: object, w: int, h: int, ox: int, oy: int) -> None:
        rng, n, g = self.rng, self.noise, self.geometry
        cx = ox + rng.uniform(0, (g.cols + 2) * CELL)
        cy = oy + rng.uniform(0, g.rows * CELL)
        a = rng.uniform(*n.occluder_cells) * CELL / 2
        b = rng.uniform(*n.occluder_cells) * CELL / 2
        colour = rng.choice([(204, 160, 130), (186, 142, 116), (70, 74, 120)])  # skin or a sleeve
        draw.ellipse([cx - a, cy - b, cx + a, cy + b], fill=colour)  # type: ignore[attr-defined]

    def _light(self, arr: np.ndarray) -> np.ndarray:
        rng, n = self.rng, self.noise
        h, w, _ = arr.shape
        bright = rng.uniform(*n.brightness)
        gx, gy = rng.uniform(-n.gradient, n.gradient), rng.uniform(-n.gradient, n.gradient)
        ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)
        field = bright * (1.0 + gx * (xs / w - 0.5) + gy * (ys / h - 0.5))
        arr = arr * field[:, :, None]
        sigma = rng.uniform(*n.pixel_sigma)
        noise = np.random.default_rng(rng.randrange(2**32)).normal(0.0, sigma, arr.shape)
        return arr + noise.astype(np.float32)


def board_view(board: Board, goal: Mapping[str, str] | None = None,
               wrong: frozenset[str] = frozenset(), last: tuple[str, str] | None = None) -> object:
    """A clean diagram of ``board`` (a PIL image): letters, goal marks, the arm, the last move.

    Goal cells carry their kind's letter in a corner (green when satisfied,
    red when not); ``wrong`` cells (misrecognised) get an orange frame.
    """
    image_mod = require("PIL.Image", "vision")
    draw_mod = require("PIL.ImageDraw", "vision")
    g = board.geometry
    w, h = image_size(g)
    img = image_mod.new("RGB", (w, h), (245, 245, 240))
    draw = draw_mod.Draw(img)
    ox = oy = MARGIN + 3
    for r in range(g.rows):
        for c in [*range(g.cols), g.tray_col]:
            cell = cell_name(r, c)
            box = _cell_box(r, c, ox, oy)
            draw.rectangle([box[0], box[1], box[2] - 1, box[3] - 1], fill=_square_colour(g, r, c))
            kind = board.at(cell)
            if kind is not None:
                draw_glyph(draw, kind, box, None, CameraNoise(), INK)
            want = goal.get(cell) if goal else None
            if want is not None:
                ok = kind == want
                draw.text((box[0] + 1, box[1]), LETTERS[want], fill=(0, 140, 0) if ok else (200, 0, 0))
            if cell in wrong:
                draw.rectangle([box[0], box[1], box[2] - 1, box[3] - 1], outline=(255, 140, 0), width=2)
    if last is not None:
        (r0, c0), (r1, c1) = cell_rc(last[0]), cell_rc(last[1])
        p0 = (ox + (c0 + 0.5) * CELL, oy + (r0 + 0.5) * CELL)
        p1 = (ox + (c1 + 0.5) * CELL, oy + (r1 + 0.5) * CELL)
        draw.line([p0, p1], fill=(30, 90, 220), width=2)
    ar, ac = cell_rc(board.arm)
    cx, cy = ox + (ac + 0.5) * CELL, oy + (ar + 0.5) * CELL
    draw.ellipse([cx - 9, cy - 9, cx + 9, cy + 9], outline=(220, 20, 60), width=2)
    return img


__all__ = ["CELL", "Camera", "CameraNoise", "GLYPHS", "KINDS", "board_view", "draw_glyph", "image_size"]
