"""Pictures of a NAMO run: PNG frames (matplotlib, Agg) and an animated GIF (Pillow).

A frame shows the map (walls, landmarks), the fog (unobserved space, grey),
objects the robot has not detected (dashed red outlines: the truth it does
not know), detected objects at their estimated pose with their
epsilon-shadows, the robot (estimate, and a small cross at its true pose),
its trajectory, the swept volumes of the moves in the plans on the stack
(orange; the current plan's path in cyan, earlier paths in grey), planned
pick/carry/return paths, and the goal.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from typing import Any

from nowplan.domains.namo.belief import NamoBelief, k_of
from nowplan.domains.namo.geometry import Manip, Pt, Region


def _mpl() -> Any:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _legend(fig: Any) -> None:
    """What the marks mean, in two rows above the map."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [
        Line2D([], [], marker="*", ls="", color="gold", markeredgecolor="black", markersize=8, label="landmark"),
        Line2D([], [], marker="*", ls="", color="red", markeredgecolor="black", markersize=9, label="goal"),
        Patch(fill=False, ls="--", ec="tab:red", label="object not detected yet (true place)"),
        Patch(color="tab:purple", alpha=0.8, label="detected object (estimate, halo: uncertainty)"),
        Line2D([], [], marker="o", ls="", color="tab:orange", markersize=8, label="robot (estimate; x: true)"),
        Line2D([], [], color="c", lw=2, label="current plan's path"),
        Patch(color="orange", alpha=0.3, label="swept volume of planned moves"),
        Patch(color="grey", alpha=0.6, label="fog (not yet observed)"),
    ]
    fig.legend(handles=handles, loc="upper center", ncol=2, fontsize=6.5, frameon=False, handlelength=1.6,
               columnspacing=1.0, borderaxespad=0.2)


def render_png(
    world: Any,
    belief: NamoBelief,
    regions: Sequence[Region] = (),
    old_paths: Sequence[Sequence[Pt]] = (),
    manips: Sequence[Manip] = (),
    goal: Pt | None = None,
    caption: str = "",
    dpi: int = 80,
) -> bytes:
    """One frame as PNG bytes."""
    plt = _mpl()
    from matplotlib.patches import Circle, Polygon, Rectangle

    geom = belief.geom
    g = geom.grid
    scale = 5.0 / max(geom.width, geom.height)
    fig = plt.figure(figsize=(max(geom.width * scale * 1.15, 3.0), max(geom.height * scale * 1.15, 2.2) + 0.9),
                     dpi=dpi)
    ax = fig.add_axes((0.02, 0.06, 0.96, 0.66))
    _legend(fig)
    ax.set_xlim(0, geom.width)
    ax.set_ylim(0, geom.height)
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    fog = (~belief.observed).reshape(g.ny, g.nx).astype(float)
    ax.imshow(fog, origin="lower", extent=(0, g.nx * g.res, 0, g.ny * g.res), cmap="Greys",
              vmin=0, vmax=2.2, alpha=0.9, interpolation="nearest", zorder=0)
    for x0, y0, x1, y1 in geom.walls:
        ax.add_patch(Rectangle((x0, y0), x1 - x0, y1 - y0, color="black", zorder=3))
    for _, p in geom.landmarks:
        ax.plot([p.x], [p.y], marker="*", color="gold", markersize=9, markeredgecolor="black", zorder=4)
    for path in old_paths:
        if len(path) >= 2:
            ax.plot([p.x for p in path], [p.y for p in path], color="grey", lw=2, alpha=0.8, zorder=5)
    for i, r in enumerate(regions):
        sh = r.shape()
        ax.add_patch(Polygon(list(sh.exterior.coords), closed=True, color="orange", alpha=0.22, lw=0, zorder=2))
        ax.plot([r.start.x, r.end.x], [r.start.y, r.end.y], color="c", lw=2, zorder=6)
    for m in manips:
        for path, col in ((m.pick_path, "tab:blue"), (m.carry_path, "tab:green"), (m.return_path, "tab:red")):
            if len(path) >= 2:
                ax.plot([p.x for p in path], [p.y for p in path], color=col, lw=1.5, ls="--", zorder=6)
    known = set(belief.objects)
    if world is not None:
        for name, box in sorted(getattr(world, "objects", {}).items()):
            x0, y0, _, _ = box.bounds
            ax.add_patch(Rectangle((x0, y0), box.w, box.h, fill=False, ls="--", lw=1,
                                   ec="tab:red" if name not in known else "dimgray", zorder=7))
    k = k_of(belief.params.eps_clear)
    for o in belief.objects.values():
        b = o.box
        grow = k * o.sigma
        ax.add_patch(Rectangle((b.bounds[0] - grow, b.bounds[1] - grow), b.w + 2 * grow, b.h + 2 * grow,
                               color="tab:purple", alpha=0.18, lw=0, zorder=7))
        ax.add_patch(Rectangle((b.bounds[0], b.bounds[1]), b.w, b.h, color="tab:purple", alpha=0.8, zorder=8))
        ax.text(b.cx, b.cy, o.name, fontsize=6, ha="center", va="center", color="white", zorder=9)
    traj = belief.trajectory
    if len(traj) >= 2:
        ax.plot([p.x for p in traj], [p.y for p in traj], color="tab:orange", lw=1, alpha=0.9, zorder=9)
    pose = belief.pose
    ax.add_patch(Circle((pose.x, pose.y), geom.robot_radius, color="tab:orange", alpha=0.85, zorder=10))
    if world is not None and hasattr(world, "pose"):
        tp = world.pose
        ax.plot([tp.x], [tp.y], marker="x", color="black", markersize=5, zorder=11)
    if goal is not None:
        ax.plot([goal.x], [goal.y], marker="*", color="red", markersize=14, markeredgecolor="black", zorder=11)
    if caption:
        fig.text(0.02, 0.015, caption[:110], fontsize=7)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return buf.getvalue()


def write_gif(frames: Sequence[bytes], path: Any, ms_per_frame: int = 400) -> None:
    """An animated GIF from PNG frames (Pillow, which matplotlib already depends on)."""
    from PIL import Image

    if not frames:
        raise ValueError("no frames to animate")
    images = [Image.open(io.BytesIO(f)).convert("RGB") for f in frames]
    size = images[0].size
    images = [im if im.size == size else im.resize(size) for im in images]
    pal = [im.convert("P", palette=Image.Palette.ADAPTIVE, colors=128) for im in images]
    pal[0].save(path, save_all=True, append_images=pal[1:], duration=ms_per_frame, loop=0, optimize=False)
