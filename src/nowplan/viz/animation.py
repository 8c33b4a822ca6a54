"""Animated GIFs with a caption: what the picture shows above, what happened below.

Used by the demos whose renderers draw plain frames (the kitchen's camera,
the marsupial bays): each frame is scaled, then a white band is added with a
header (what the marks mean, the same on every frame) and the frame's own
caption (e.g. ``after (push bottom)``).  Pillow comes with matplotlib.
"""

from __future__ import annotations

import io
import textwrap
from collections.abc import Sequence
from pathlib import Path
from typing import Any

CHAR_PX = 7  # about how wide a character of the caption font is


def _font(size: int) -> Any:
    from PIL import ImageFont

    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow < 10.1: one bitmap font size
        return ImageFont.load_default()


def captioned_frame(png: bytes, header: str, caption: str, scale: float = 1.0) -> Any:
    """One frame with its header and caption under it, as a Pillow RGB image."""
    from PIL import Image, ImageDraw

    im = Image.open(io.BytesIO(png)).convert("RGB")
    if scale != 1.0:
        im = im.resize((round(im.width * scale), round(im.height * scale)), Image.Resampling.LANCZOS)
    width = max(im.width, 360)
    per_line = max(20, width // CHAR_PX - 2)
    lines = textwrap.wrap(header, per_line) + textwrap.wrap(caption, per_line)[:2]
    band = 8 + 15 * len(lines)
    out = Image.new("RGB", (width, im.height + band), "white")
    out.paste(im, ((width - im.width) // 2, 0))
    draw = ImageDraw.Draw(out)
    font = _font(12)
    n_header = len(textwrap.wrap(header, per_line))
    for i, line in enumerate(lines):
        draw.text((6, im.height + 4 + 15 * i), line, fill="#333333" if i < n_header else "black", font=font)
    return out


def write_captioned_gif(frames: Sequence[bytes], path: Path, header: str, captions: Sequence[str],
                        ms_per_frame: int = 700, scale: float = 1.0) -> Path:
    """An animated GIF of ``frames`` (PNG bytes), each with ``header`` and its caption below it."""
    from PIL import Image

    if not frames:
        raise ValueError("no frames to animate")
    images = [captioned_frame(f, header, c, scale) for f, c in zip(frames, [*captions, *[""] * len(frames)])]
    size = (max(im.width for im in images), max(im.height for im in images))
    images = [im if im.size == size else _pad(im, size) for im in images]
    pal = [im.convert("P", palette=Image.Palette.ADAPTIVE, colors=128) for im in images]
    pal[0].save(path, save_all=True, append_images=pal[1:], duration=ms_per_frame, loop=0, optimize=False)
    return path


def _pad(im: Any, size: tuple[int, int]) -> Any:
    from PIL import Image

    out = Image.new("RGB", size, "white")
    out.paste(im, (0, 0))
    return out


def frames_of(events: Sequence[dict[str, Any]]) -> tuple[list[bytes], list[str]]:
    """The PNG frames a trace holds as data URIs, with their captions."""
    import base64

    pngs: list[bytes] = []
    caps: list[str] = []
    prefix = "data:image/png;base64,"
    for e in events:
        img = e.get("image")
        if e.get("event") == "frame" and isinstance(img, str) and img.startswith(prefix):
            pngs.append(base64.b64decode(img[len(prefix):]))
            caps.append(str(e.get("caption") or ""))
    return pngs, caps
