"""A picture of a logistics state: cities, their locations, vehicles and packages.

Matplotlib (Agg).  Each city is a ring of locations (the airport filled
pink) around its name; trucks are blue squares and airplanes orange
triangles at their location; a package is a small labelled disc at its
location, or listed inside the vehicle that carries it.  The world's true
state is drawn (the belief of this domain is the same when nothing fails
silently).
"""

from __future__ import annotations

import io
import math
from collections import defaultdict
from typing import Any


def render_png(world: Any, belief: Any = None, dpi: int = 80) -> bytes:
    """The world's state as PNG bytes (the ``renderer`` of the logistics domain)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle

    state = world.state
    city_of = {str(loc): str(c) for loc, c in state.facts("in_city")}
    airports = {str(a[0]) for a in state.facts("airport")}
    at = {str(o): str(loc) for o, loc in state.facts("at")}
    inside = {str(p): str(v) for p, v in state.facts("in")}
    cities = sorted(set(city_of.values()))
    locs_of: dict[str, list[str]] = defaultdict(list)
    for loc, c in sorted(city_of.items()):
        locs_of[c].append(loc)
    pos: dict[str, tuple[float, float]] = {}
    for i, c in enumerate(cities):
        ang = 2 * math.pi * i / max(len(cities), 1) + math.pi / 2
        cx, cy = 3.0 * math.cos(ang), 3.0 * math.sin(ang)
        pos[c] = (cx, cy)
        locs = locs_of[c]
        for j, loc in enumerate(locs):
            a = 2 * math.pi * j / max(len(locs), 1)
            pos[loc] = (cx + 0.9 * math.cos(a), cy + 0.9 * math.sin(a))
    fig, ax = plt.subplots(figsize=(7, 6), dpi=dpi)
    ax.set_aspect("equal")
    ax.axis("off")
    for c in cities:
        ax.text(*pos[c], c, ha="center", va="center", fontsize=9, color="#555")
    for loc, (x, y) in pos.items():
        if loc in city_of:
            ax.add_patch(Circle((x, y), 0.22, fc="#f4b6c8" if loc in airports else "#dddddd", ec="#333"))
            ax.text(x, y - 0.36, loc, ha="center", va="top", fontsize=6)
    vehicles = sorted(set(inside.values()) | {o for o in at if o.startswith(("truck", "plane", "airplane"))})
    offsets: dict[str, int] = defaultdict(int)
    for v in vehicles:
        where = at.get(v)
        if where is None or where not in pos:
            continue
        loc = where
        k = offsets[loc]
        offsets[loc] += 1
        x, y = pos[loc][0] + 0.28 + 0.28 * k, pos[loc][1] + 0.22
        plane = "plane" in v or "airplane" in v
        ax.plot([x], [y], marker="^" if plane else "s", color="tab:orange" if plane else "tab:blue", markersize=9)
        load = sorted(p for p, w in inside.items() if w == v)
        ax.text(x, y + 0.18, v + (f" [{', '.join(load)}]" if load else ""), fontsize=6, ha="center")
    ground: dict[str, list[str]] = defaultdict(list)
    for p, loc in sorted(at.items()):
        if p not in vehicles and loc in pos:
            ground[loc].append(p)
    for loc, ps in ground.items():
        for k, p in enumerate(ps):
            x, y = pos[loc][0] - 0.3 - 0.2 * k, pos[loc][1] - 0.05
            ax.add_patch(Circle((x, y), 0.08, fc="tab:green", ec="black", lw=0.5))
            ax.text(x, y + 0.12, p, fontsize=5.5, ha="center")
    xs = [p[0] for p in pos.values()] or [0.0]
    ys = [p[1] for p in pos.values()] or [0.0]
    ax.set_xlim(min(xs) - 1.3, max(xs) + 1.5)
    ax.set_ylim(min(ys) - 1.1, max(ys) + 1.1)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return buf.getvalue()

