"""Argument helpers shared by the subcommands."""

from __future__ import annotations

import argparse
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

N = TypeVar("N", int, float)


def existing_file(value: str) -> Path:
    p = Path(value)
    if not p.is_file():
        raise argparse.ArgumentTypeError(f"no such file: '{value}' (check the path)")
    return p


def criticality_arg(value: str) -> str:
    """``--criticality``: ``auto`` (derive the hierarchy) or an existing criticality file."""
    if value == "auto":
        return value
    return str(existing_file(value))


def _number(value: str, cast: Callable[[str], N], what: str, ok: Callable[[N], bool], bound: str) -> N:
    """``cast(value)`` if it parses and passes ``ok``; else an argparse error naming what was expected."""
    try:
        v = cast(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected {what}, got '{value}'") from None
    if not ok(v):
        raise argparse.ArgumentTypeError(f"expected {bound}, got {v}")
    return v


def nonneg_int(value: str) -> int:
    return _number(value, int, "a whole number", lambda v: v >= 0, "a number >= 0")


def positive_int(value: str) -> int:
    return _number(value, int, "a whole number", lambda v: v > 0, "a number > 0")


def positive_float(value: str) -> float:
    return _number(value, float, "a number", lambda v: v > 0, "a number > 0")


def probability(value: str) -> float:
    return _number(value, float, "a probability", lambda v: 0.0 <= v <= 1.0, "a probability in [0, 1]")
