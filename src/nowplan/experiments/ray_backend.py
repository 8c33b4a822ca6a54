"""The Ray backend: the same runs as :class:`~nowplan.experiments.runner.LocalBackend`, on Ray.

Ray is an optional extra (``pip install 'nowplan[ray]'``) imported only
when this backend runs.  Without ``address`` a local Ray instance with
``jobs`` CPUs is started (and shut down afterwards); with ``address``
(``auto`` or ``HOST:PORT``) the sweep joins an existing cluster, whose
nodes must have the same nowplan installed.  At most as many runs as
there are CPUs are in flight, so a run's hard time limit is counted from
about when it starts; an overrunning task is cancelled with
``force=True`` (its worker is killed) and recorded as a timeout.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Sequence
from typing import Any

from nowplan.errors import require
from nowplan.experiments.records import RunConfig, RunRecord, crashed, timed_out
from nowplan.experiments.runner import GRACE_S, OnRecord, execute_dict, hard_limit

log = logging.getLogger(__name__)


class RayBackend:
    name = "ray"

    def __init__(self, jobs: int | None = None, address: str | None = None, grace: float = GRACE_S) -> None:
        self.jobs = jobs
        self.address = address
        self.grace = grace

    def _init(self, ray: Any) -> bool:
        """Start or join Ray unless already initialised; True if we must shut it down."""
        if ray.is_initialized():
            return False
        kwargs: dict[str, Any] = {
            "include_dashboard": False,
            "log_to_driver": False,
            "logging_level": logging.WARNING,
            "configure_logging": True,
        }
        if self.address:
            ray.init(address=self.address, **kwargs)
        else:
            ray.init(num_cpus=self.jobs, **kwargs)
        return True

    def run(self, configs: Sequence[RunConfig], on_record: OnRecord) -> None:
        ray = require("ray", "ray")
        started = self._init(ray)
        try:
            self._run(ray, configs, on_record)
        finally:
            if started:
                ray.shutdown()

    def _run(self, ray: Any, configs: Sequence[RunConfig], on_record: OnRecord) -> None:
        remote = ray.remote(num_cpus=1, max_retries=0)(execute_dict)
        slots = self.jobs or max(1, int(ray.cluster_resources().get("CPU", 1)))
        todo = list(reversed(configs))
        inflight: dict[Any, tuple[RunConfig, float, float]] = {}  # ref -> (config, start, deadline)
        try:
            while todo or inflight:
                while todo and len(inflight) < slots:
                    cfg = todo.pop()
                    now = time.monotonic()
                    inflight[remote.remote(cfg.to_dict())] = (cfg, now, now + hard_limit(cfg.time_limit, self.grace))
                next_deadline = min(d for _, _, d in inflight.values())
                ready, _ = ray.wait(
                    list(inflight), num_returns=1, timeout=max(0.0, next_deadline - time.monotonic())
                )
                for ref in ready:
                    cfg, start, _ = inflight.pop(ref)
                    on_record(self._collect(ray, ref, cfg, start))
                now = time.monotonic()
                for ref, (cfg, start, deadline) in list(inflight.items()):
                    if now >= deadline:
                        del inflight[ref]
                        ray.cancel(ref, force=True)
                        log.warning("run %s cancelled after %.1f s", cfg.label(), now - start)
                        on_record(timed_out(cfg, hard_limit(cfg.time_limit, self.grace), now - start))
        finally:
            for ref in inflight:
                ray.cancel(ref, force=True)

    @staticmethod
    def _collect(ray: Any, ref: Any, cfg: RunConfig, start: float) -> RunRecord:
        try:
            return RunRecord.from_dict(ray.get(ref))
        except Exception as exc:  # noqa: BLE001 - a lost worker is a crashed run, the sweep goes on
            return crashed(cfg, error=repr(exc), reason=f"Ray task failed: {type(exc).__name__}",
                           wall_s=time.monotonic() - start)
