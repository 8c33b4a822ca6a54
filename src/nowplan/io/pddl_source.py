"""PDDL source text: reading files, locating constructs by line, parser errors.

:func:`parse_source` runs the maintained ``pddl`` parser and turns its
errors (lark syntax errors with a line and column, missing requirements,
its own type and constant checks) into one-line
:class:`nowplan.errors.PDDLError` messages naming the file and, whenever it
can be found, the line.
"""

from __future__ import annotations

import functools
import re
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from nowplan.errors import PDDLError, UnsupportedPDDLError


@dataclass(frozen=True)
class Source:
    """A file's text with comments blanked, for locating constructs by line."""

    path: str
    text: str

    @functools.cached_property
    def code(self) -> str:
        return re.sub(r";[^\n]*", lambda m: " " * len(m.group(0)), self.text.lower())

    def line_of(self, pattern: str, start: int = 0) -> int | None:
        m = re.compile(pattern).search(self.code, start)
        return self.code.count("\n", 0, m.start()) + 1 if m else None

    def offset_of(self, pattern: str) -> int:
        m = re.compile(pattern).search(self.code)
        return m.start() if m else 0

    def line_of_token(self, token: str, start: int = 0) -> int | None:
        return self.line_of(r"(?<![\w?-])" + re.escape(token.lower()) + r"(?![\w-])", start)

    def line_of_atom(self, predicate: str, start: int = 0) -> int | None:
        return self.line_of(r"\(\s*" + re.escape(predicate.lower()) + r"(?=[\s()])", start)

    def error(self, message: str, line: int | None = None, unsupported: bool = False) -> PDDLError:
        cls = UnsupportedPDDLError if unsupported else PDDLError
        return cls(message, path=self.path, line=line)


def read_source(path: str | Path) -> Source:
    p = Path(path)
    if not p.exists():
        raise PDDLError("file not found (check the path)", path=str(path))
    if not p.is_file():
        raise PDDLError("not a regular file", path=str(path))
    try:
        return Source(str(path), p.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError) as exc:
        raise PDDLError(f"cannot read the file: {exc}", path=str(path)) from exc


@functools.lru_cache(maxsize=2)
def _parser(kind: str) -> Any:
    """The ``pddl`` package's parser, its LALR tables cached on disk by Lark.

    Building the tables takes ~0.15 s per parser and process; Lark's own
    ``cache`` (a file in the temporary directory, keyed by the grammar and
    options) loads them in a few milliseconds, so ``nowplan plan`` starts fast.
    """
    from lark import Lark, Transformer
    from pddl.parser import GRAMMAR_FILE, PARSERS_DIRECTORY

    if kind == "domain":
        from pddl.parser.domain import DomainParser as Base
    else:
        from pddl.parser.problem import ProblemParser as Base

    class Cached(Base):  # type: ignore[misc]
        def __init__(self) -> None:
            Transformer.__init__(self)
            self._transformer = self.transformer_cls()
            self._parser = Lark(GRAMMAR_FILE.read_text(), parser="lalr", import_paths=[PARSERS_DIRECTORY],
                                start=self.start_symbol, transformer=self._transformer, cache=True)

    return Cached()


def parse_source(src: Source, kind: str) -> Any:
    """Run the ``pddl`` parser, turning its errors into :class:`PDDLError` with a line."""
    from lark.exceptions import UnexpectedCharacters, UnexpectedEOF, UnexpectedInput, UnexpectedToken
    from pddl.exceptions import PDDLMissingRequirementError

    old_limit = getattr(sys, "tracebacklimit", None)
    try:
        return _parser(kind)(src.text)
    except UnexpectedInput as exc:
        _parser.cache_clear()  # the transformer keeps state; start afresh
        line = getattr(exc, "line", None)
        line = line if isinstance(line, int) and line > 0 else None
        if isinstance(exc, UnexpectedCharacters):
            what = f"unexpected character {exc.char!r}"
        elif isinstance(exc, UnexpectedToken):
            tok = "end of file" if exc.token.type == "$END" else repr(str(exc.token))
            what = f"unexpected {tok}"
        elif isinstance(exc, UnexpectedEOF):
            what = "unexpected end of file"
        else:  # pragma: no cover - other lark input errors
            what = str(exc).splitlines()[0]
        if what.startswith("unexpected ':'") or "':" in what:
            what += " (unknown requirement or section keyword?)"
        col = getattr(exc, "column", None)
        where = f" at column {col}" if isinstance(col, int) and col > 0 else ""
        raise src.error(f"PDDL syntax error: {what}{where}", line) from exc
    except PDDLMissingRequirementError as exc:
        _parser.cache_clear()
        req = str(exc.requirement).lstrip(":")
        keyword = {
            "disjunctive-preconditions": r"\(\s*(or|imply)[\s(]",
            "equality": r"\(\s*=[\s(]",
            "existential-preconditions": r"\(\s*exists[\s(]",
            "universal-preconditions": r"\(\s*forall[\s(]",
            "typing": r"\s-\s",
        }.get(req)
        line = src.line_of(keyword, src.offset_of(r"\(:")) if keyword else None
        raise src.error(
            f"the file uses a feature that needs the requirement :{req} but does not declare it "
            "in (:requirements ...)",
            line,
        ) from exc
    except Exception as exc:  # the parser's own checks (types, constants, ...)
        _parser.cache_clear()
        msg = " ".join(str(exc).split()) or type(exc).__name__
        quoted = re.findall(r"'([^'\s]+)'", msg)
        line = None
        for tok in quoted:
            line = src.line_of_token(tok, src.offset_of(r"\(:"))
            if line is not None:
                break
        raise src.error(f"invalid PDDL {kind}: {msg}", line) from exc
    finally:
        if old_limit is None:
            if hasattr(sys, "tracebacklimit"):
                del sys.tracebacklimit  # the pddl parser leaves it at 0 after an error
        else:
            sys.tracebacklimit = old_limit
