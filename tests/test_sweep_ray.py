"""The Ray backend gives the same records as the local one (local Ray started by the test)."""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.experiments.runner import LocalBackend
from nowplan.experiments.store import Store
from nowplan.experiments.sweep import SweepSpec, SweepState, run_sweep

ray = pytest.importorskip(
    "ray", reason="ray is not installed: pip install -e '.[test-ray]' (make test does) to run the Ray test"
)


def test_ray_backend_matches_local(tmp_path: Path) -> None:
    from nowplan.experiments.ray_backend import RayBackend

    spec = SweepSpec("logistics", ("small",), ("hpn", "hpn+aggressive"), (0, 1, 2), 60.0)
    with Store(tmp_path / "local.sqlite") as st:
        local = run_sweep(spec, st, LocalBackend(jobs=2), progress=False)
    with Store(tmp_path / "ray.sqlite") as st:
        remote = run_sweep(spec, st, RayBackend(jobs=2), progress=False)
    assert not ray.is_initialized()  # the backend shut down the Ray it started
    assert local.state is SweepState.COMPLETE and remote.state is SweepState.COMPLETE
    assert len(local.records) == len(remote.records) == 6
    assert [r.decisions() for r in local.records] == [r.decisions() for r in remote.records]
    assert all(r.outcome == "reached" for r in remote.records)
