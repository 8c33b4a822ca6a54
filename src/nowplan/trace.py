"""Structured JSONL traces of planning and execution.

Every event is one JSON object per line with at least ``seq`` (0, 1, …),
``t`` (seconds since the run started, wall clock) and ``event``.  The event
kinds and their fields are documented in ``docs/trace-format.md``; the
viewer (``nowplan view``) reads exactly that.
"""

from __future__ import annotations

import json
import logging
import time
from pathlib import Path
from typing import IO, Any

log = logging.getLogger(__name__)

EVENTS = (
    "run_start",
    "plan",
    "plan_failed",
    "push",
    "pop",
    "step",
    "action",
    "observation",
    "failure",
    "replan",
    "exogenous",
    "frame",
    "note",
    "cycle",  # the progress guard saw the agent's own actions bring it back (nowplan.acting.progress)
    "disagreement",  # at the end of a run: the goal atoms on which belief and world disagree
    "run_end",
)


class Trace:
    """Collects events in memory and, if given a path, streams them to a JSONL file."""

    def __init__(self, path: str | Path | None = None) -> None:
        self.events: list[dict[str, Any]] = []
        self._t0 = time.perf_counter()
        self._fh: IO[str] | None = None
        self.path = Path(path) if path is not None else None
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._fh = self.path.open("w", encoding="utf-8")

    def emit(self, event: str, **fields: Any) -> dict[str, Any]:
        if event not in EVENTS:
            raise ValueError(f"unknown trace event {event!r}; known: {', '.join(EVENTS)}")
        rec = {"seq": len(self.events), "t": round(time.perf_counter() - self._t0, 6), "event": event}
        rec.update(fields)
        self.events.append(rec)
        if self._fh is not None:
            self._fh.write(json.dumps(rec, default=str) + "\n")
            self._fh.flush()
        log.debug("trace %s %s", event, fields)
        return rec

    def close(self) -> None:
        if self._fh is not None:
            self._fh.close()
            self._fh = None

    def __enter__(self) -> Trace:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def of(self, event: str) -> list[dict[str, Any]]:
        return [e for e in self.events if e["event"] == event]


