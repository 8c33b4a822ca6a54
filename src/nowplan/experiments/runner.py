"""Executing runs: one configuration in this process, or many in worker processes.

:func:`execute` runs one :class:`RunConfig` here and always returns a
:class:`RunRecord` (an exception becomes a ``crashed`` record with its
text).  :class:`LocalBackend` runs each configuration in its own worker
process, at most ``jobs`` at a time, and kills a worker that overruns its
hard time limit (the strategy's own soft limit plus a grace period), so a
hung run can never stall a sweep.
"""

from __future__ import annotations

import logging
import multiprocessing as mp
import os
import signal
import sys
import time
import traceback
from collections import deque
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from typing import Any, Protocol

from nowplan.experiments.records import RunConfig, RunRecord, RunStatus, crashed, timed_out

log = logging.getLogger(__name__)

OnRecord = Callable[[RunRecord], None]


class Backend(Protocol):
    """Runs configurations and reports each finished record (in any order)."""

    name: str

    def run(self, configs: Sequence[RunConfig], on_record: OnRecord) -> None: ...


GRACE_S = 5.0  # at least this long past the soft limit before a worker is killed


def hard_limit(time_limit: float, grace: float = GRACE_S) -> float:
    """Seconds after which a worker is killed: the soft limit plus a grace period."""
    return time_limit + max(grace, 0.1 * time_limit)


def execute(config: RunConfig) -> RunRecord:
    """Build the scenario, run it under the strategy and summarise it; never raises."""
    t0 = time.perf_counter()
    try:
        from nowplan.acting.run import run_episode
        from nowplan.acting.strategy import parse_strategy
        from nowplan.domains.registry import get_domain

        from nowplan.experiments.faults import apply_faults, split_scenario

        base, faults = split_scenario(config.scenario)  # "small?failure=0.5": a fault level
        spec = get_domain(config.domain)
        make = spec.scenario(base)
        strategy = parse_strategy(config.strategy, base_planner=spec.planner, time_limit=config.time_limit)
        episode = make(config.seed)
        apply_faults(episode, faults)
        metrics = run_episode(episode, strategy, config.seed).to_dict()
    except Exception as exc:  # a crashing run is recorded and the sweep goes on
        log.debug("run %s crashed", config.label(), exc_info=True)
        return crashed(
            config,
            error=traceback.format_exc(),
            reason=f"{type(exc).__name__}: {exc}",
            wall_s=time.perf_counter() - t0,
        )
    return RunRecord(
        config,
        RunStatus.DONE,
        str(metrics["outcome"]),
        reason=str(metrics.get("reason", "")),
        metrics=metrics,
        wall_s=time.perf_counter() - t0,
    )


def execute_dict(config: dict[str, Any]) -> dict[str, Any]:
    """:func:`execute` on plain dicts (what crosses process and Ray boundaries)."""
    return execute(RunConfig.from_dict(config)).to_dict()


# -- local worker processes -------------------------------------------------------------


def default_start_method() -> str:
    """fork where there is one: cheap, and workers see domains registered at run time (tests, notebooks)."""
    return "fork" if "fork" in mp.get_all_start_methods() else "spawn"


def die_with_parent() -> None:
    """Linux: have the kernel kill this worker if the sweep process dies (even by SIGKILL)."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        pr_set_pdeathsig = 1
        libc.prctl(pr_set_pdeathsig, signal.SIGKILL)
    except (OSError, AttributeError):  # pragma: no cover - best effort
        pass


def _worker(conn: Connection, config: dict[str, Any], parent_pid: int) -> None:
    die_with_parent()
    if os.getppid() != parent_pid:  # the parent died before prctl took effect
        os._exit(1)
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # the parent decides what an interrupt means
    try:
        conn.send(execute_dict(config))
    finally:
        conn.close()


@dataclass
class _Active:
    config: RunConfig
    process: Any  # multiprocessing.process.BaseProcess
    started: float
    deadline: float


class LocalBackend:
    """Each run in its own worker process, ``jobs`` at a time, with a hard time limit."""

    name = "local"

    def __init__(self, jobs: int | None = None, start_method: str | None = None, grace: float = GRACE_S) -> None:
        self.jobs = max(1, jobs or os.cpu_count() or 1)
        self.grace = grace
        self.start_method = start_method or default_start_method()

    def run(self, configs: Sequence[RunConfig], on_record: OnRecord) -> None:
        ctx: Any = mp.get_context(self.start_method)
        if self.start_method == "fork":
            import nowplan.acting.run  # noqa: F401 - imported once here, not in every worker
        todo = deque(configs)
        active: dict[Connection, _Active] = {}
        try:
            while todo or active:
                while todo and len(active) < self.jobs:
                    cfg = todo.popleft()
                    reader, writer = ctx.Pipe(duplex=False)
                    proc = ctx.Process(
                        target=_worker, args=(writer, cfg.to_dict(), os.getpid()), daemon=True,
                        name=f"nowplan-run-{cfg.key[:8]}",
                    )
                    proc.start()
                    writer.close()
                    now = time.monotonic()
                    active[reader] = _Active(cfg, proc, now, now + hard_limit(cfg.time_limit, self.grace))
                next_deadline = min(a.deadline for a in active.values())
                ready = wait(list(active), timeout=max(0.0, next_deadline - time.monotonic()))
                for conn in ready:
                    assert isinstance(conn, Connection)
                    a = active.pop(conn)
                    on_record(self._collect(conn, a))
                now = time.monotonic()
                for conn, a in list(active.items()):
                    if now >= a.deadline:
                        del active[conn]
                        a.process.kill()
                        a.process.join()
                        conn.close()
                        log.warning("run %s killed after %.1f s", a.config.label(), now - a.started)
                        limit = hard_limit(a.config.time_limit, self.grace)
                        on_record(timed_out(a.config, limit, now - a.started))
        finally:
            for conn, a in active.items():  # interrupted: stop the workers still running
                a.process.kill()
                a.process.join()
                conn.close()

    @staticmethod
    def _collect(conn: Connection, a: _Active) -> RunRecord:
        try:
            data = conn.recv()
        except (EOFError, OSError):
            data = None
        finally:
            conn.close()
        a.process.join()
        elapsed = time.monotonic() - a.started
        if data is None:
            code = a.process.exitcode
            how = f"killed by signal {-code}" if code is not None and code < 0 else f"exit code {code}"
            return crashed(a.config, error=f"worker process died ({how}) without a result",
                           reason=f"worker died ({how})", wall_s=elapsed)
        return RunRecord.from_dict(data)
