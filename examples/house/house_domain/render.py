"""A picture of the true house for `nowplan run --frames` and `nowplan view` (matplotlib, no display)."""

from __future__ import annotations

import io
from typing import Any

from house_domain.scenarios import DOORS

BOX = {"kitchen": (0, 1), "hall": (1, 1), "bath": (2, 1), "study": (1, 0), "bedroom": (2, 0)}  # grid cells


def render(world: Any, belief: Any) -> bytes:
    """PNG of ``world.state``: rooms as boxes, doors green (open), orange (closed) or red (locked)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle

    state = world.state
    fig, ax = plt.subplots(figsize=(4.5, 3))
    for room, (x, y) in BOX.items():
        ax.add_patch(Rectangle((x * 1.5, y * 1.5), 1.3, 1.3, fill=False))
        ax.text(x * 1.5 + 0.05, y * 1.5 + 1.15, room, fontsize=8)
    for door, (a, b, _, _) in DOORS.items():
        (xa, ya), (xb, yb) = BOX[a], BOX[b]
        color = ("green" if state.value(("open", (door,))) else
                 "orange" if state.value(("unlocked", (door,))) else "red")
        ax.plot([(xa + xb) * 0.75 + 0.65], [(ya + yb) * 0.75 + 0.65], "s", color=color, markersize=9)
    for (room,) in state.facts("robot_in"):
        x, y = BOX[str(room)]
        ax.plot([x * 1.5 + 0.65], [y * 1.5 + 0.55], "o", color="steelblue", markersize=16)
        held = [str(i) for (i,) in state.facts("holding")]
        ax.text(x * 1.5 + 0.45, y * 1.5 + 0.2, "robot" + (f"+{held[0]}" if held else ""), fontsize=7)
    for n, (item, room) in enumerate(sorted(state.facts("at"), key=str)):
        x, y = BOX[str(room)]
        ax.text(x * 1.5 + 0.1, y * 1.5 + 0.9 - 0.2 * n, str(item), fontsize=8, color="purple")
    ax.set_xlim(-0.1, 4.4)
    ax.set_ylim(-0.1, 2.9)
    ax.axis("off")
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=80)
    plt.close(fig)
    return buf.getvalue()
