"""PDDL source files: reading them with one-line errors.

:func:`read_source` reads a file's text (UTF-8 with or without a byte-order mark,
else Latin-1, as in some old IPC files); a missing file or a directory give a :class:`nowplan.errors.PDDLError` naming the path.
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
        data = p.read_bytes()
    except OSError as exc:
        raise PDDLError(f"cannot read the file: {' '.join(str(exc).split())}", path=str(path)) from exc
    try:
        text = data.decode("utf-8-sig")  # a byte-order mark is skipped
    except UnicodeDecodeError:
        text = data.decode("latin-1")  # e.g. an author's name in a comment of an old IPC file
    return Source(str(path), text)
