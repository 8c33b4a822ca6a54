"""The error taxonomy: one root exception, typed subclasses.

Every error raised on purpose by nowplan derives from :class:`NowplanError`.
Messages name the place (file, line, argument) and the fix, so the CLI can
print ``str(err)`` as one line and exit non-zero.
"""

from __future__ import annotations


class NowplanError(Exception):
    """Root of every error nowplan raises on purpose."""

    exit_code = 2


class ModelError(NowplanError):
    """A domain, operator, atom or goal is malformed (unknown predicate, arity...)."""


class ContradictoryGoalError(ModelError):
    """A goal asks for two incompatible values of the same fluent."""


class PDDLError(NowplanError):
    """A PDDL file cannot be read or uses a feature nowplan does not support."""

    def __init__(self, message: str, *, path: str | None = None, line: int | None = None) -> None:
        where = ""
        if path is not None:
            where = f"{path}:{line}: " if line is not None else f"{path}: "
        super().__init__(where + message)
        self.path = path
        self.line = line


class UnsupportedPDDLError(PDDLError):
    """The file is valid PDDL but uses a requirement outside nowplan's fragment."""


class CompilationBoundError(UnsupportedPDDLError):
    """Compiling ADL to STRIPS exceeds a bound (disjuncts, operators, quantifier instances)."""


class ScenarioError(NowplanError):
    """An unknown or malformed domain / scenario / strategy name or parameter."""


class MissingExtraError(NowplanError):
    """An optional dependency is missing; the message names the extra to install."""

    def __init__(self, module: str, extra: str) -> None:
        super().__init__(
            f"the optional dependency '{module}' is not installed; "
            f"install it with: pip install 'nowplan[{extra}]'"
        )
        self.module = module
        self.extra = extra


class UsageError(NowplanError):
    """Command-line arguments that cannot work together."""


class ExecutionError(NowplanError):
    """A world could not execute an action it was given (not a modelled failure)."""


class TraceError(NowplanError):
    """A trace file is malformed."""


class StoreError(NowplanError):
    """A result store cannot be used (e.g. written by an incompatible version)."""


def require(module: str, extra: str):  # type: ignore[no-untyped-def]
    """Import an optional dependency lazily, or raise :class:`MissingExtraError`."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as exc:  # pragma: no cover - depends on the environment
        raise MissingExtraError(module, extra) from exc


def one_line(message: str) -> str:
    """``message`` as one printable line: a line break becomes a space and any other control
    character (SQLite and file contents can carry ``\\x1c``, which ``str.splitlines`` also breaks at)
    its escape, so an error printed for the user stays the one line it promises."""
    out = []
    for ch in message:
        if ch in "\r\n":
            out.append(" ")
        elif ch.isprintable() or ch == "\t":
            out.append(ch)
        else:
            out.append(ascii(ch)[1:-1])
    return "".join(out)
