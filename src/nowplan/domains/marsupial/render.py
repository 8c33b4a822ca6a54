"""Pictures of a marsupial state: the map with vehicles and packages, and every cargo bay.

Matplotlib with the Agg backend (no display needed); :func:`render_png`
returns PNG bytes.  In the map, pink circles are airports, lines are roads
(dashed: flights), squares are trucks, the triangle is the plane and small
coloured discs are packages on the ground.  Each bay is drawn as its grid:
beige storage, grey load region, coloured packages, the loader in red.
"""

from __future__ import annotations

import io
import math
from typing import Any

from nowplan.domains.marsupial.grid import Hold, cells, door_package, load_anchor
from nowplan.domains.marsupial.problems import MapSpec


def _positions(spec: MapSpec) -> dict[str, tuple[float, float]]:
    pos: dict[str, tuple[float, float]] = {}
    n = len(spec.cities)
    for i, c in enumerate(spec.cities):
        ang = 2 * math.pi * i / n + math.pi / 2
        cx, cy = 3.2 * math.cos(ang), 3.2 * math.sin(ang)
        pos[c.airport] = (cx * 0.7, cy * 0.7)
        others = c.places[1:]
        for j, q in enumerate(others):
            a2 = ang + (j - (len(others) - 1) / 2) * 0.55
            pos[q] = (cx + 0.9 * math.cos(a2), cy + 0.9 * math.sin(a2))
    return pos


def _color(pkg: str) -> Any:
    import matplotlib

    idx = int("".join(ch for ch in pkg if ch.isdigit()) or 0)
    return matplotlib.colormaps["tab10"](idx % 10)


def render_png(spec: MapSpec, state: Any, title: str = "", dpi: int = 70) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    vehicles = [*spec.trucks, spec.plane]
    fig = plt.figure(figsize=(11, 6))
    grid = fig.add_gridspec(len(vehicles), 2, width_ratios=(2.2, 1))
    ax = fig.add_subplot(grid[:, 0])
    pos = _positions(spec)
    airports = [c.airport for c in spec.cities]
    for i, a in enumerate(airports):
        for b in airports[i + 1 :]:
            ax.plot(*zip(pos[a], pos[b], strict=True), color="#bbbbbb", lw=0.6, ls="--", zorder=0)
    for c in spec.cities:
        for a, b in c.roads:
            ax.plot(*zip(pos[a], pos[b], strict=True), color="#666666", lw=1.2, zorder=1)
        for q in c.places:
            ax.scatter(*pos[q], s=260, color="#f4a6c6" if q == c.airport else "#dddddd",
                       edgecolor="k", zorder=2)
            ax.annotate(q, pos[q], fontsize=6, ha="center", va="center", zorder=3)
        ax.annotate(f"{c.name} ({c.layout})", (pos[c.airport][0], pos[c.airport][1] - 0.45),
                    fontsize=7, ha="center", color="#444444")
    ground: dict[str, list[str]] = {}
    for args in state.facts("at"):
        obj, loc = str(args[0]), str(args[1])
        if obj in vehicles:
            x, y = pos[loc]
            marker = "^" if obj == spec.plane else "s"
            ax.scatter(x + 0.22, y + 0.22, marker=marker, s=110, color="#3366cc", zorder=4)
            ax.annotate(obj, (x + 0.22, y + 0.42), fontsize=6, ha="center", color="#3366cc")
        else:
            ground.setdefault(loc, []).append(obj)
    for loc, pkgs in ground.items():
        for k, pkg in enumerate(sorted(pkgs)):
            x, y = pos[loc]
            ax.scatter(x - 0.25 + 0.13 * k, y - 0.28, s=45, color=_color(pkg), edgecolor="k", zorder=5)
            ax.annotate(pkg, (x - 0.25 + 0.13 * k, y - 0.45), fontsize=5, ha="center")
    ax.set_aspect("equal")
    ax.axis("off")
    if title:
        ax.set_title(title, fontsize=9)
    shapes = dict(state.facts("shape"))
    for r, veh in enumerate(vehicles):
        bx = fig.add_subplot(grid[r, 1])
        hold = state.value(("cargo", (veh,)))
        if isinstance(hold, Hold):
            _draw_bay(bx, hold, door_package(str(state.value(("door", (veh,))))), shapes, Rectangle)
        bx.set_title(f"{veh}" + (f"  holding {hold.held}" if isinstance(hold, Hold) and hold.held else ""),
                     fontsize=7, pad=2)
        bx.axis("off")
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return buf.getvalue()


def _draw_bay(ax: Any, hold: Hold, door: str | None, shapes: dict[Any, Any], Rectangle: Any) -> None:
    rows, cols = hold.rows, hold.cols
    for r in range(rows):
        for c in range(cols):
            face = "#f2e6c9" if c < cols - 2 else "#d9d9d9"
            ax.add_patch(Rectangle((c, rows - 1 - r), 1, 1, facecolor=face, edgecolor="#999999", lw=0.5))
    placed = [(n, s, a) for n, s, a in hold.items]
    if door is not None and door in shapes:
        placed.append((door, shapes[door], load_anchor(cols)))
    for name, shape, anchor in placed:
        for r, c in cells(shape, anchor):
            ax.add_patch(Rectangle((c, rows - 1 - r), 1, 1, facecolor=_color(name), edgecolor="k", lw=0.5))
        ax.annotate(name, (anchor[1] + 0.5, rows - 1 - anchor[0] + 0.5), fontsize=5, ha="center", va="center")
    lr, lc = hold.loader
    ax.add_patch(Rectangle((lc + 0.2, rows - 1 - lr + 0.2), 0.6, 0.6, facecolor="#d62728", edgecolor="k"))
    ax.set_xlim(0, cols)
    ax.set_ylim(0, rows)
    ax.set_aspect("equal")
