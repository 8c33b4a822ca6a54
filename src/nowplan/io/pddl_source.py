"""PDDL source files: reading them with one-line errors.

:func:`read_source` reads a file's text; a missing file, a directory or
undecodable bytes give a :class:`nowplan.errors.PDDLError` naming the path.
(The syntax is read by :mod:`nowplan.io.sexpr` and :mod:`nowplan.io.pddl_syntax`.)
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from nowplan.errors import PDDLError


@dataclass(frozen=True)
class Source:
    """A file's path and text."""

    path: str
    text: str


def read_source(path: str | Path) -> Source:
    p = Path(path)
    if not p.exists():
        raise PDDLError("file not found (check the path)", path=str(path))
    if not p.is_file():
        raise PDDLError("not a regular file", path=str(path))
    try:
        return Source(str(path), p.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise PDDLError(f"cannot read the file: {' '.join(str(exc).split())}", path=str(path)) from exc
