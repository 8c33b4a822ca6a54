"""The README's commands stay true: every line of its ``sh``/``bash`` blocks runs as printed.

Convention (README and docs/development.md): a line whose comment holds ``[long]`` runs for
minutes or installs things and is skipped; ``make TARGET`` lines are checked with ``make -n``
(the target exists and its recipe expands), since they build a virtual environment.  Every
other line runs in order, in a scratch folder that sees the repository's files read-only
through symbolic links, with ``.venv/bin/nowplan`` (and a bare ``nowplan``) running this
interpreter's nowplan.  The fast test checks the convention and that each ``nowplan`` line
names a real subcommand; the other runs the lines (about 15 s).
"""

from __future__ import annotations

import os
import re
import shlex
import stat
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
LONG = "[long]"


def shell_lines(text: str) -> list[str]:
    """The command lines of the ```sh / ```bash blocks, in order (blank and comment-only lines dropped)."""
    out: list[str] = []
    inside = False
    for line in text.splitlines():
        fence = line.strip()
        if fence.startswith("```"):
            inside = not inside and fence[3:].strip() in ("sh", "bash", "shell", "console")
            continue
        if inside and line.strip() and not line.strip().startswith("#"):
            out.append(line.strip())
    return out


def is_long(line: str) -> bool:
    return "#" in line and LONG in line.split("#", 1)[1]


def command_of(line: str) -> str:
    """The line without its trailing comment."""
    return line.split(" #", 1)[0].strip() if " #" in line else line


def test_the_parser_and_the_convention() -> None:
    text = "a\n```sh\nmake demo   # quick\n# only a comment\nnowplan run  # [long] minutes\n```\n```text\nno\n```\n"
    lines = shell_lines(text)
    assert lines == ["make demo   # quick", "nowplan run  # [long] minutes"]
    assert [is_long(x) for x in lines] == [False, True]
    assert command_of(lines[0]) == "make demo"


def test_every_readme_command_names_a_real_subcommand_or_target() -> None:
    from nowplan.cli import COMMANDS

    subcommands = set(COMMANDS)
    makefile = (ROOT / "Makefile").read_text()
    lines = shell_lines(README.read_text(encoding="utf-8"))
    assert any("nowplan" in x for x in lines) and any(not is_long(x) for x in lines)
    for line in lines:
        words = shlex.split(command_of(line))
        if words[0] == "make":
            assert re.search(rf"^{re.escape(words[1])}:", makefile, re.M), line
        elif words[0].endswith("nowplan"):
            assert words[1] in subcommands, line


def _scratch(tmp: Path) -> dict[str, str]:
    """A folder that looks like a fresh clone after ``make demo``: links to the sources, a nowplan shim."""
    for item in ROOT.iterdir():
        if item.name not in (".venv", "out", ".git") and not item.name.startswith("."):
            (tmp / item.name).symlink_to(item)
    bin_dir = tmp / ".venv" / "bin"
    bin_dir.mkdir(parents=True)
    shim = bin_dir / "nowplan"
    shim.write_text(f'#!/bin/sh\nexec "{sys.executable}" -c "import sys; from nowplan.cli import main; '
                    f'sys.exit(main())" "$@"\n')
    shim.chmod(shim.stat().st_mode | stat.S_IXUSR)
    env = dict(os.environ)
    env["PATH"] = f"{bin_dir}{os.pathsep}{env.get('PATH', '')}"
    src = str(ROOT / "src")
    env["PYTHONPATH"] = src + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    env["MPLBACKEND"] = "Agg"
    return env


@pytest.mark.timeout(600)
def test_the_readme_commands_run_as_printed(tmp_path: Path) -> None:
    env = _scratch(tmp_path)
    for line in shell_lines(README.read_text(encoding="utf-8")):
        if is_long(line):
            continue
        cmd = command_of(line)
        words = shlex.split(cmd)
        if words[0] == "make":  # builds .venv/: only check that the recipe expands
            cmd = f"make -n -f {ROOT / 'Makefile'} {' '.join(words[1:])}"
        proc = subprocess.run(["bash", "-c", cmd], cwd=tmp_path, env=env, capture_output=True, text=True,
                              timeout=300)
        assert proc.returncode == 0, f"README line failed: {line}\n{proc.stdout[-2000:]}\n{proc.stderr[-2000:]}"
    assert (tmp_path / "out" / "demo" / "namo" / "trace.html").is_file()  # the README says so
