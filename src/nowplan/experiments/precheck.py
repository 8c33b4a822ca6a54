"""A sweep's runs checked before any of them runs: a refused strategy or fault level is bad input.

:meth:`SweepSpec.validate <nowplan.experiments.sweep.SweepSpec.validate>` checks names (domain,
scenarios, strategy switches and their combinations, fault-level syntax) without running domain
code.  What only a built episode can tell (a switch the domain declares unsupported, ``domain-planner``
on a domain without a planner, a belief the engine cannot use, a fault knob the world lacks, a scenario
file that cannot be read) is checked here: each scenario is built for the sweep's first seed, its faults
applied, and the executive of each strategy constructed, not run (:func:`nowplan.acting.run.make_runner`),
exactly as the run would.  The first :class:`~nowplan.errors.NowplanError` becomes one line naming the
configuration and the fix (exit 2 in ``nowplan sweep``), and nothing is stored.

The check runs in a worker process, as the runs do, with the runs' hard time limit: a scenario that
hangs or crashes is not the sweep's to refuse (its runs are recorded as killed or crashed, and the sweep
exits 1).  Mechanisms refuse what they cannot work with when the executive is built
(``Mechanism.check``: the monitor switches on a belief that is not a point state, or on predicates
tested on the belief), so those refusals are caught here too.
"""

from __future__ import annotations

import logging
import multiprocessing as mp
import os
from multiprocessing.connection import Connection
from typing import Any

from nowplan.errors import NowplanError, ScenarioError
from nowplan.experiments.records import RunConfig
from nowplan.experiments.runner import default_start_method, die_with_parent

log = logging.getLogger(__name__)


def refusal(configs: list[RunConfig]) -> str | None:
    """The first configuration of ``configs`` its run would refuse, as ``"LABEL: why"``; else None.

    Runs domain code in this process: scenarios are built once each (with their faults) and every
    strategy's executive is constructed on them.  A scenario that fails with an error that is not a
    :class:`~nowplan.errors.NowplanError` is left to its runs.
    """
    from nowplan.acting.run import make_runner
    from nowplan.acting.strategy import parse_strategy
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import apply_faults, split_scenario

    episodes: dict[tuple[str, str, int], Any] = {}
    for c in configs:
        try:
            spec = get_domain(c.domain)
            strategy = parse_strategy(c.strategy, base_planner=spec.planner, time_limit=c.time_limit)
            key = (c.domain, c.scenario, c.seed)
            if key not in episodes:
                base, faults = split_scenario(c.scenario)
                episode = spec.scenario(base)(c.seed)
                apply_faults(episode, faults)
                episodes[key] = episode
            make_runner(episodes[key], strategy, c.seed)
        except NowplanError as err:
            return f"{c.label()}: {err}"
        except Exception:  # noqa: BLE001 - a crashing scenario is recorded by its runs, not refused here
            log.info("pre-check of %s crashed; its runs will record it", c.label(), exc_info=True)
    return None


def _worker(conn: Connection, configs: list[dict[str, Any]]) -> None:
    die_with_parent()  # as the runs' workers: a killed sweep leaves no check behind
    try:
        conn.send(refusal([RunConfig.from_dict(c) for c in configs]))
    finally:
        conn.close()


def check_runs(configs: list[RunConfig], timeout: float, start_method: str | None = None) -> None:
    """Raise :class:`~nowplan.errors.ScenarioError` if a run of ``configs`` would be refused.

    :func:`refusal` in a worker process, stopped after ``timeout`` seconds (then nothing is refused:
    the runs meet what the check did not finish).
    """
    if not configs:
        return
    ctx: Any = mp.get_context(start_method or default_start_method())
    reader, writer = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_worker, args=(writer, [c.to_dict() for c in configs]), daemon=True,
                       name=f"nowplan-precheck-{os.getpid()}")
    proc.start()
    writer.close()
    why: str | None = None
    try:
        if reader.poll(timeout):
            try:
                why = reader.recv()
            except (EOFError, OSError):  # the worker died: its runs will say how
                log.info("the sweep's pre-check worker died without a verdict; the runs go ahead")
        else:
            log.warning("the sweep's pre-check took over %.0f s; the runs go ahead unchecked", timeout)
    finally:
        reader.close()
        if proc.is_alive():
            proc.kill()
        proc.join()
    if why is not None:
        raise ScenarioError(why)
