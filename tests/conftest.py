from __future__ import annotations

import os
from collections.abc import Callable, Iterator

import pytest
from hypothesis import settings

# Property tests draw their examples deterministically (from the test's own source), so a run of
# the suite is reproducible and a failure on CI fails the same way on a laptop.
# NOWPLAN_HYPOTHESIS=explore draws fresh random examples instead, to search wider.
settings.register_profile("seeded", derandomize=True, database=None)
settings.register_profile("explore", derandomize=False)
settings.load_profile(os.environ.get("NOWPLAN_HYPOTHESIS", "seeded"))


@pytest.fixture
def mode(monkeypatch: pytest.MonkeyPatch) -> Iterator[Callable[[str], None]]:
    """``mode("python")`` / ``mode("c")``: which code the next search or heuristic uses."""
    from nowplan.planning import native

    def set_mode(m: str) -> None:
        monkeypatch.setenv(native.ENV, "1" if m == "python" else "0")

    yield set_mode
