"""S-expressions of PDDL text, with the line of every token.

:func:`parse_sexprs` turns text into a list of :class:`SList` (parenthesised
lists) whose items are :class:`Token` (lower-cased words, each with its line)
or nested lists.  Comments (``;`` to the end of the line) are skipped; a
stray ``)``, a missing ``)`` or a character no PDDL token uses is a
:class:`nowplan.errors.PDDLError` naming the line.  Nesting is bounded
(:data:`MAX_DEPTH`) so hostile input cannot exhaust the stack.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from nowplan.errors import PDDLError

MAX_DEPTH = 200
# a PDDL token: names, variables, keywords, numbers, operators (=, <=, +, -, *, /)
_TOKEN = re.compile(r"[^\s()]+")
_BAD = re.compile(r"[\[\]{}\"'`#|\\]")


@dataclass(frozen=True)
class Token:
    text: str
    line: int

    def __str__(self) -> str:
        return self.text


@dataclass(frozen=True)
class SList:
    items: tuple[Token | SList, ...]
    line: int  # the line of the opening parenthesis
    end_line: int = 0

    def __len__(self) -> int:
        return len(self.items)

    def head(self) -> str:
        """The first item's text when it is a token ('' otherwise)."""
        return self.items[0].text if self.items and isinstance(self.items[0], Token) else ""

    def __str__(self) -> str:
        return "(" + " ".join(str(i) for i in self.items) + ")"


Item = Token | SList


def parse_sexprs(text: str, path: str | None = None) -> list[Item]:
    """All top-level items of ``text`` (normally one ``(define ...)``)."""
    stack: list[tuple[list[Item], int]] = []
    top: list[Item] = []
    line = 1
    pos = 0
    n = len(text)
    while pos < n:
        c = text[pos]
        if c == "\n":
            line += 1
            pos += 1
        elif c.isspace():
            pos += 1
        elif c == ";":
            end = text.find("\n", pos)
            pos = n if end < 0 else end
        elif c == "(":
            if len(stack) >= MAX_DEPTH:
                raise PDDLError(f"PDDL syntax error: parentheses nested deeper than {MAX_DEPTH}",
                                path=path, line=line)
            stack.append(([], line))
            pos += 1
        elif c == ")":
            if not stack:
                raise PDDLError("PDDL syntax error: unexpected ')' (no '(' to close)", path=path, line=line)
            items, start = stack.pop()
            lst = SList(tuple(items), start, line)
            (stack[-1][0] if stack else top).append(lst)
            pos += 1
        else:
            m = _TOKEN.match(text, pos)
            assert m is not None
            word = m.group(0)
            bad = _BAD.search(word)
            if bad is not None:
                col = pos + bad.start() - (text.rfind("\n", 0, pos) + 1) + 1
                raise PDDLError(f"PDDL syntax error: unexpected character {bad.group(0)!r} at column {col}",
                                path=path, line=line)
            tok = Token(word.lower(), line)
            (stack[-1][0] if stack else top).append(tok)
            pos = m.end()
    if stack:
        raise PDDLError(
            f"PDDL syntax error: unexpected end of file: the '(' opened on line {stack[-1][1]} is never closed",
            path=path, line=stack[-1][1],
        )
    return top
