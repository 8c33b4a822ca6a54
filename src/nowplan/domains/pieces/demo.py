"""``nowplan demo pieces``: an animated run, the camera's view beside the board.

The seed's task scheduler on a shuffled board: the means-ends plan is
executed, a person disturbs the board (``--failure-prob`` is used as the
disturbance probability per piece move), every move is followed by a camera
frame that the trained recogniser reads, and the monitor chooses between
the seed's three alternatives.  Writes ``pieces.gif`` (left: the camera
frame the robot saw; right: the true board, goal letters green when met and
red when not, orange frames on misrecognised cells, the last move in blue,
the arm circled) and ``pieces-trace.jsonl`` whose ``frame`` events carry the
same pictures as data URIs, plus the HTML viewer when available.
"""

from __future__ import annotations

import argparse
import base64
import importlib.util
import io
import logging
from collections import Counter
from pathlib import Path
from typing import Any

import numpy as np

from nowplan.acting.monitor import MonitorConfig, monitor_settings
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.pieces.board import Board
from nowplan.domains.pieces.model import goal_reached
from nowplan.domains.pieces.render import board_view
from nowplan.domains.pieces.scenarios import SIZES, generate, make_episode
from nowplan.domains.pieces.vision import misrecognised, recognizer
from nowplan.errors import require
from nowplan.trace import Trace

log = logging.getLogger(__name__)

CAPTION_H = 34


def compose(camera: np.ndarray, board: Any, caption: str) -> Any:
    """Camera frame | board diagram, with a caption strip below (a PIL image)."""
    image_mod = require("PIL.Image", "vision")
    draw_mod = require("PIL.ImageDraw", "vision")
    cam = image_mod.fromarray(camera)
    w = cam.width + 8 + board.width
    h = max(cam.height, board.height) + CAPTION_H
    out = image_mod.new("RGB", (w, h), (250, 250, 246))
    out.paste(cam, (0, 0))
    out.paste(board, (cam.width + 8, 0))
    d = draw_mod.Draw(out)
    d.text((4, h - CAPTION_H + 2), caption[:100], fill=(20, 20, 20))
    if len(caption) > 100:
        d.text((4, h - CAPTION_H + 16), caption[100:200], fill=(20, 20, 20))
    return out


def png_bytes(img: Any) -> bytes:
    buf = io.BytesIO()
    img.save(buf, format="PNG", optimize=True)
    return buf.getvalue()


def render_png(world: Any, belief: Any) -> bytes:
    """The domain's renderer: a fresh camera frame beside the true board, as PNG."""
    truth: Board = world.board
    _, frame = world.look()
    wrong = frozenset(misrecognised(belief.board.labels(), truth)) if hasattr(belief, "board") else frozenset()
    return png_bytes(compose(frame, board_view(truth, None, wrong), "camera | board"))


class _Recorder:
    """Collects a picture after every recognised frame and emits it to the trace."""

    def __init__(self, world: Any, goal: dict[str, str], trace: Trace) -> None:
        self.world = world
        self.goal = goal
        self.trace = trace
        self.frames: list[Any] = []
        self.n = 0

    def snapshot(self, camera: np.ndarray, caption: str, last: tuple[str, str] | None,
                 wrong: frozenset[str]) -> None:
        img = compose(camera, board_view(self.world.board, self.goal, wrong, last), caption)
        self.frames.append(img)
        buf = io.BytesIO()
        img.save(buf, format="JPEG", quality=82)  # noisy camera frames compress badly as PNG
        uri = "data:image/jpeg;base64," + base64.b64encode(buf.getvalue()).decode("ascii")
        self.trace.emit("frame", n=self.n, image=uri, caption=caption)

    def __call__(self, info: dict[str, Any]) -> None:
        """The belief's look hook: the first frame of this step, the truth, what went wrong."""
        act, obs = info["action"], info["observation"]
        self.n += 1
        wrong = frozenset(misrecognised(info["labels"], self.world.board))
        looks = len(info["frames"])
        parts = [f"step {self.n}: {act.name} {' '.join(str(a) for a in act.args)}"
                 + ("" if obs.success else " (failed)")]
        if obs.exogenous:
            parts.append("; ".join(obs.exogenous))
        if looks > 1:
            parts.append(f"surprise: looked {looks} times")
        if wrong:
            parts.append(f"{len(wrong)} cell(s) misread")
        self.snapshot(obs.data["image"], " | ".join(parts), (str(act.args[1]), str(act.args[2])), wrong)


def main(args: argparse.Namespace) -> int:
    size = SIZES[args.size]
    task = generate(size, args.seed, f"pieces-{args.size}")
    rate = float(args.failure_prob)
    rec = recognizer(0)
    print(f"nowplan demo pieces: {size.rows}×{size.cols} board, {size.pieces} pieces, seed {args.seed}, "
          f"a person disturbs the board after a move with probability {rate:g}")
    print(rec.summary())
    print(f"goal: each of the {len(task.goal)} pieces on its goal cell\n")
    out: Path = args.out
    out.mkdir(parents=True, exist_ok=True)
    trace_path = out / "trace.jsonl"
    with Trace(trace_path) as trace:
        ep = make_episode(task, args.seed, rate, rec=rec)
        recorder = _Recorder(ep.world, task.goal, trace)
        ep.belief.on_look = recorder
        _, first = ep.world.look()
        recorder.snapshot(first, "start: the camera's view (left) and the true board (right)", None,
                          frozenset())
        with monitor_settings(MonitorConfig()):
            metrics = run_episode(ep, parse_strategy("hpn+monitor"), seed=args.seed, trace=trace)
        choices = Counter(e.get("alternative") for e in trace.of("note") if e.get("alternative"))
        done = goal_reached(ep.world.board, task.goal)
        _, last = ep.world.look()
        recorder.snapshot(last, f"end: goal {'reached' if done else 'NOT reached'}, arm travel "
                          f"{ep.world.travel:.1f}", None, frozenset())
    gif = out / "pieces.gif"
    frames = recorder.frames
    durations = [1400] + [900] * (len(frames) - 2) + [2500] if len(frames) > 1 else [2500]
    frames[0].save(gif, save_all=True, append_images=frames[1:], duration=durations, loop=0,
                   optimize=False)
    blog = ep.belief.log
    print(metrics.summary())  # the same lines as every demo, then this domain's own
    if done != (metrics.outcome.value == "reached"):
        print(f"true board: goal {'reached' if done else 'NOT reached'}")
    print(f"arm travel: {ep.world.travel:.1f} cells, {ep.world.piece_moves} piece moves, "
          f"{ep.world.exogenous_events} disturbance(s)")
    print(f"monitor choices: {dict(choices) or 'none (no surprise)'}")
    print(f"camera: {blog.looks} frames recognised, {blog.relooks} re-looks, "
          f"{blog.cleared_by_relook} false alarm(s) cleared by re-looking")
    print(f"\ntrace: {trace_path}\nanimation: {gif} ({len(frames)} frames)")
    if importlib.util.find_spec("nowplan.viz.viewer") is not None:
        from nowplan.viz.viewer import write_viewer

        page = out / "trace.html"
        write_viewer(trace_path, page)
        print(f"viewer: {page} (open it in a browser)")
    return 0 if done else 1
