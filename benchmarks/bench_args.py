"""Argument helpers shared by the benchmark scripts (imported from beside them)."""

from __future__ import annotations


def span(text: str) -> list[int]:
    """``0-3``, ``5,8,10`` or ``3-5,8``: the integers named, in order."""
    out: list[int] = []
    for part in text.split(","):
        lo, _, hi = part.partition("-")
        out.extend(range(int(lo), int(hi or lo) + 1))
    return out


class Hang(Exception):
    """A run outlived its SIGALRM deadline (:func:`alarm` raises it)."""


def alarm(signum: int, frame: object) -> None:
    """A SIGALRM handler: ``signal.signal(signal.SIGALRM, alarm)``."""
    raise Hang()
