"""Camera renders of the true kitchen with the belief's particles drawn on top.

The image comes from the fixed camera through PyBullet's TinyRenderer
(``getCameraImage`` in DIRECT mode); particles are projected with the same
view and projection matrices and drawn as dots coloured like their object,
brighter for heavier particles.  :func:`write_gif` stacks frames into an
animated GIF (Pillow, which matplotlib already depends on).
"""

from __future__ import annotations

import base64
import io
from pathlib import Path
from typing import Any

import numpy as np

from nowplan.domains.kitchen import scene as S

W, H = 320, 240


def render_array(world: Any, belief: Any) -> np.ndarray:
    sc = world.scene
    world.sync()
    view, proj = S.camera_matrices(sc, W, H)
    img = sc.p.getCameraImage(W, H, view, proj, renderer=sc.p.ER_TINY_RENDERER, physicsClientId=sc.client)
    rgb = np.reshape(np.asarray(img[2], dtype=np.uint8), (H, W, 4))[:, :, :3].copy()
    if belief is not None:
        v = np.asarray(view, dtype=float).reshape(4, 4).T
        pm = np.asarray(proj, dtype=float).reshape(4, 4).T
        for o in belief.objects:
            if o == belief.held:
                continue
            pts = belief.world_of(o)
            w = belief.particles[o].weights
            hom = np.c_[pts + np.array([0, 0, S.SIZES[o][2]]), np.ones(len(pts))] @ (pm @ v).T
            ndc = hom[:, :3] / hom[:, 3:4]
            us = ((ndc[:, 0] + 1) / 2 * W).astype(int)
            vs = ((1 - ndc[:, 1]) / 2 * H).astype(int)
            colour = np.array(S.COLOURS[o][:3]) * 255
            for u, vv, wi in zip(us, vs, w / w.max(), strict=True):
                if 1 <= u < W - 1 and 1 <= vv < H - 1:
                    shade = colour * (0.3 + 0.7 * wi)
                    rgb[vv - 1 : vv + 2, u - 1 : u + 2] = shade.astype(np.uint8)
    return rgb


def render_png(world: Any, belief: Any) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(render_array(world, belief)).save(buf, format="PNG")
    return buf.getvalue()


def data_uri(png: bytes) -> str:
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def write_gif(frames: list[bytes], path: Path, ms: int = 700) -> Path:
    from PIL import Image

    images = [Image.open(io.BytesIO(f)).convert("P") for f in frames]
    if images:
        images[0].save(path, save_all=True, append_images=images[1:], duration=ms, loop=0)
    return path
