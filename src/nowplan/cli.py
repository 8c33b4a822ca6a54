"""The ``nowplan`` command line: one entry point, one module per subcommand.

Each module in :mod:`nowplan.commands` exposes ``register(subparsers)``,
which adds its parser and sets ``func`` (a callable taking the parsed
arguments and returning an exit code).  Errors derived from
:class:`nowplan.errors.NowplanError` are printed as one line, never a
traceback.
"""

from __future__ import annotations

import argparse
import atexit
import gc
import importlib
import logging
import sys
from collections.abc import Sequence

from typing import Any

from nowplan.errors import NowplanError, one_line

# subcommand modules under nowplan.commands, in --help order
COMMANDS = ("plan", "run", "criticality", "demo", "domains", "sweep", "report", "reproduce", "view")


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors that name the fix."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, f"{self.prog}: error: {message} (see '{self.prog} --help')\n")


class _Version(argparse.Action):
    """``--version``, reading the installed version only when asked."""

    def __call__(self, parser: argparse.ArgumentParser, namespace: Any, values: Any,
                 option_string: str | None = None) -> None:
        import nowplan

        parser.exit(0, f"nowplan {nowplan.__version__}\n")


def build_parser(only: str | None = None) -> argparse.ArgumentParser:
    """The parser; with ``only``, just that subcommand's module is imported (a fast start)."""
    parser = _Parser(
        prog="nowplan",
        description="Hierarchical planning and acting under uncertainty.",
    )
    parser.add_argument("--version", action=_Version, nargs=0, help="print the version and exit")
    parser.add_argument("-v", "--verbose", action="count", default=0, help="log more (-v info, -vv debug)")
    parser.add_argument("--import", dest="imports", action="append", default=[], metavar="MOD",
                        help="import a domain module (its SPEC) before running; repeatable "
                             "(like NOWPLAN_DOMAINS=MOD,...)")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for name in COMMANDS if only is None else (only,):
        try:
            mod = importlib.import_module(f"nowplan.commands.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"nowplan.commands.{name}":
                raise
            continue
        mod.register(sub)
    return parser


def _subcommand(argv: list[str]) -> str | None:
    """The subcommand ``argv`` names, if it comes before any help flag (then only it is loaded)."""
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ("-h", "--help"):
            return None
        if a == "--import":
            i += 2  # its value is a module name, not a subcommand
            continue
        if not a.startswith("-"):
            return a if a in COMMANDS else None
        i += 1
    return None


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    # the interpreter's last collections at exit walk the whole heap, a grounded task's millions of
    # objects included (IPC parking p02: ~0.9 s of a 4.8 s `nowplan plan`), and find nothing a command
    # needs freed: the heap is frozen first (atexit runs before them); once, however often main runs
    atexit.unregister(gc.freeze)
    atexit.register(gc.freeze)
    parser = build_parser(_subcommand(argv))
    args = parser.parse_args(argv)
    logging.basicConfig(
        level=[logging.WARNING, logging.INFO, logging.DEBUG][min(args.verbose, 2)],
        format="%(levelname)s %(name)s: %(message)s",
    )
    if args.imports:
        from nowplan.domains.registry import load_module

        try:
            for mod in args.imports:
                load_module(mod)
        except NowplanError as err:
            print(f"nowplan: error: {one_line(str(err))}", file=sys.stderr)
            return err.exit_code
    if not getattr(args, "func", None):
        parser.print_help()
        return 2
    try:
        return int(args.func(args) or 0)
    except NowplanError as err:
        print(f"nowplan {args.command}: error: {one_line(str(err))}", file=sys.stderr)
        return err.exit_code
    except BrokenPipeError:  # output piped into head & co.
        sys.stderr.close()
        return 0
    except OSError as err:  # a path the command cannot read or write (a directory, a missing parent...)
        logging.getLogger(__name__).debug("file error", exc_info=True)
        where = f"{err.filename}: " if err.filename is not None else ""
        print(f"nowplan {args.command}: error: {one_line(where + str(err.strerror or err))}; give another path "
              f"(see 'nowplan {args.command} --help' for what each path names)", file=sys.stderr)
        return 2
    except MemoryError:  # a search that outgrew the machine: say so in one line, not a traceback
        print(f"nowplan {args.command}: error: out of memory; bound the search (--max-nodes N or a "
              f"smaller --time-limit, where the command has them) or give a smaller problem", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("nowplan: interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
