from __future__ import annotations

import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT / "src") not in sys.path:  # running without an installed package
    sys.path.insert(0, str(ROOT / "src"))


@pytest.fixture
def mode(monkeypatch: pytest.MonkeyPatch) -> Iterator[Callable[[str], None]]:
    """``mode("python")`` / ``mode("c")``: which code the next search or heuristic uses."""
    from nowplan.planning import native

    def set_mode(m: str) -> None:
        monkeypatch.setenv(native.ENV, "1" if m == "python" else "0")

    yield set_mode
