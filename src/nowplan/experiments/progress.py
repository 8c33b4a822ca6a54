"""Progress bars for long commands (reproductions, sweeps, benchmarks).

One place decides how a long command shows progress: a tqdm bar on
standard error with counts, rate and an estimate of the time left, drawn
as soon as it is made (so a command shows something within a moment of
starting), and silent when standard error is not a terminal (pipes, CI
logs, tests) or when ``NOWPLAN_PROGRESS=0``.  ``NOWPLAN_PROGRESS=1`` draws
it even off a terminal.
"""

from __future__ import annotations

import os
import sys
from typing import Any, TextIO


def wanted(stream: TextIO | None = None) -> bool:
    """Whether a bar should be drawn on ``stream`` (standard error by default)."""
    forced = os.environ.get("NOWPLAN_PROGRESS", "").strip()
    if forced in ("0", "1"):
        return forced == "1"
    s = stream if stream is not None else sys.stderr
    try:
        return bool(s.isatty())
    except (AttributeError, ValueError):  # a closed or replaced stream
        return False


def bar(total: int | None, desc: str, unit: str = "run", *, initial: int = 0,
        stream: TextIO | None = None, enabled: bool | None = None, leave: bool = True,
        bar_format: str | None = None) -> Any:
    """A tqdm bar for ``total`` steps called ``desc``; a no-op bar when progress is not wanted."""
    from tqdm import tqdm

    out = stream if stream is not None else sys.stderr
    on = wanted(out) if enabled is None else enabled
    return tqdm(total=total, initial=initial, desc=desc, unit=unit, file=out, disable=not on,
                dynamic_ncols=True, mininterval=0.25, leave=leave, bar_format=bar_format)


def starting(desc: str, what: str = "loading the domains", enabled: bool | None = None) -> Any:
    """A bar without a total, drawn at once while a command loads what it needs; close it after."""
    return bar(None, f"{desc}: {what}", "step", leave=False, enabled=enabled, bar_format="{desc} [{elapsed}]")


def echo(line: str) -> None:
    """Print ``line`` to standard output without tearing a bar that is being drawn."""
    from tqdm import tqdm

    tqdm.write(line, file=sys.stdout)
