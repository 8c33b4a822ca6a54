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
from collections.abc import Callable
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


class Lazy:
    """A field of a trace event made only when the event is read or written: the executive's plan
    records (every step's pre-image as sorted text) cost a fifth of an HPN run on gripper-250 under
    ``--criticality auto`` when nothing read them.  What ``make`` reads must not change afterwards
    (plans and goals are immutable)."""

    __slots__ = ("_make",)

    def __init__(self, make: Callable[[], Any]) -> None:
        self._make = make

    def value(self) -> Any:
        return self._make()

    def __repr__(self) -> str:  # a debug log of the fields shows the value
        return repr(self._make())


class Trace:
    """Collects events in memory and, if given a path, streams them to a JSONL file.

    A field given as :class:`Lazy` is made when the event is written to the file (at once) or when
    :attr:`events` is first read after it; the events read are always complete."""

    def __init__(self, path: str | Path | None = None) -> None:
        self._events: list[dict[str, Any]] = []
        self._pending: list[dict[str, Any]] = []  # events with a Lazy field not made yet
        self._t0 = time.perf_counter()
        self._fh: IO[str] | None = None
        self.path = Path(path) if path is not None else None
        if self.path is not None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            self._fh = self.path.open("w", encoding="utf-8")

    @property
    def events(self) -> list[dict[str, Any]]:
        """Every event so far, each with all its fields made."""
        if self._pending:
            for rec in self._pending:
                _make_fields(rec)
            self._pending.clear()
        return self._events

    def emit(self, event: str, **fields: Any) -> dict[str, Any]:
        if event not in EVENTS:
            raise ValueError(f"unknown trace event {event!r}; known: {', '.join(EVENTS)}")
        rec = {"seq": len(self._events), "t": round(time.perf_counter() - self._t0, 6), "event": event}
        rec.update(fields)
        self._events.append(rec)
        if any(type(v) is Lazy for v in fields.values()):
            if self._fh is not None:
                _make_fields(rec)
            else:
                self._pending.append(rec)
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


def _make_fields(rec: dict[str, Any]) -> None:
    for k, v in rec.items():
        if type(v) is Lazy:
            rec[k] = v.value()
