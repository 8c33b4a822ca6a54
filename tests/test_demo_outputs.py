"""Every demo writes out/demo/<domain>/ with a trace, a viewer page and a captioned animation."""

from __future__ import annotations

import io
from pathlib import Path

import pytest

from nowplan.cli import main as cli_main
from nowplan.viz.animation import captioned_frame, frames_of, write_captioned_gif


def _png(w: int = 40, h: int = 30) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.new("RGB", (w, h), "red").save(buf, format="PNG")
    return buf.getvalue()


def test_captioned_gif_has_every_frame_and_a_caption_band(tmp_path: Path) -> None:
    from PIL import Image

    frame = captioned_frame(_png(), "header " * 30, "after (move a b)", scale=2.0)
    assert frame.width >= 80 and frame.height > 60  # the band under the scaled frame
    assert frame.getpixel((frame.width - 1, frame.height - 1)) == (255, 255, 255)
    gif = write_captioned_gif([_png(), _png(50, 30)], tmp_path / "a.gif", "what the marks mean", ["start", "end"])
    with Image.open(gif) as im:
        assert im.n_frames == 2
    with pytest.raises(ValueError):
        write_captioned_gif([], tmp_path / "b.gif", "h", [])


def test_frames_of_reads_png_data_uris_only() -> None:
    import base64

    uri = "data:image/png;base64," + base64.b64encode(_png()).decode()
    events = [{"event": "frame", "image": uri, "caption": "c"}, {"event": "frame", "image": "x.png"},
              {"event": "action"}]
    pngs, caps = frames_of(events)
    assert len(pngs) == 1 and caps == ["c"]


def test_logistics_renderer_draws_a_state() -> None:
    from nowplan.domains.logistics import SPEC, episode

    ep = episode("tiny", 0)
    assert SPEC.renderer is not None
    png = SPEC.renderer(ep.world, ep.belief)
    assert png.startswith(b"\x89PNG")


@pytest.mark.slow
@pytest.mark.parametrize("domain", ["logistics", "namo", "pieces", "marsupial", "kitchen"])
def test_each_demo_writes_its_folder(domain: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                     capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    assert cli_main(["demo", domain]) == 0
    out = capsys.readouterr().out
    folder = tmp_path / "out" / "demo" / domain
    gifs = list(folder.glob("*.gif"))
    assert (folder / "trace.jsonl").is_file() and (folder / "trace.html").is_file() and gifs, sorted(folder.iterdir())
    assert f"animation: out/demo/{domain}/" in out and f"viewer: out/demo/{domain}/trace.html" in out
    assert "outcome: reached" in out and "wall time of the whole run" in out


def test_pybullet_is_imported_without_its_banner() -> None:
    import subprocess
    import sys

    pytest.importorskip("pybullet")
    code = "from nowplan.domains.kitchen.scene import pybullet; pybullet(); print('ok')"
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == "ok\n" and "pybullet build time" not in proc.stderr
    plain = subprocess.run([sys.executable, "-c", "import pybullet"], capture_output=True, text=True, timeout=120)
    assert "pybullet build time" in plain.stdout + plain.stderr  # what the quiet import hides
