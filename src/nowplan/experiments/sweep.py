"""Sweeps: every (scenario, strategy, seed) of a domain, run once, stored, resumable.

:func:`run_sweep` skips the configurations already in the store, runs the
rest on a backend (local worker processes or Ray), writes each record the
moment it arrives (one transaction each), shows a progress bar with the
count done and an ETA on stderr, and returns a :class:`SweepResult` whose
:meth:`SweepResult.summary` is the table printed at the end.
"""

from __future__ import annotations

import enum
import logging
import re
import sys
import time
from collections import Counter
from dataclasses import dataclass, field
from typing import TextIO

from nowplan.errors import ScenarioError
from nowplan.experiments.records import RunConfig, RunRecord, RunStatus
from nowplan.experiments.runner import Backend, LocalBackend
from nowplan.experiments.stats import Estimate, group_records, text_table
from nowplan.experiments.store import Store

log = logging.getLogger(__name__)

_RANGE = re.compile(r"^(\d+)\s*-\s*(\d+)$")
MAX_SEEDS = 1_000_000


def parse_seeds(text: str) -> list[int]:
    """``"0-9"``, ``"0,3,5"``, ``"7"`` or a mix (``"0-4,10"``) -> sorted distinct seeds."""
    seeds: set[int] = set()
    for part in (p.strip() for p in text.split(",")):
        if not part:
            continue
        m = _RANGE.match(part)
        if m:
            lo, hi = int(m.group(1)), int(m.group(2))
            if hi < lo:
                raise ScenarioError(f"seed range '{part}' runs backwards; write it as '{hi}-{lo}'")
            if hi - lo >= MAX_SEEDS:
                raise ScenarioError(f"seed range '{part}' is too large (at most {MAX_SEEDS} seeds)")
            seeds.update(range(lo, hi + 1))
        elif part.isdigit():
            seeds.add(int(part))
        else:
            raise ScenarioError(
                f"malformed seeds '{text}': expected a range '0-9', a list '0,3,5' or one seed '7'"
            )
    if not seeds:
        raise ScenarioError("no seeds given: use e.g. --seeds 0-9")
    return sorted(seeds)


def parse_names(text: str, what: str) -> list[str]:
    names = [n.strip() for n in text.split(",") if n.strip()]
    if not names:
        raise ScenarioError(f"no {what} given")
    return list(dict.fromkeys(names))  # drop repeats, keep order


@dataclass(frozen=True)
class SweepSpec:
    domain: str
    scenarios: tuple[str, ...]
    strategies: tuple[str, ...]
    seeds: tuple[int, ...]
    time_limit: float = 600.0

    def validate(self) -> None:
        """Unknown domain, scenario or strategy names -> :class:`ScenarioError` listing valid ones."""
        from nowplan.acting.strategy import parse_strategy
        from nowplan.domains.registry import get_domain

        if self.time_limit <= 0:
            raise ScenarioError(f"the time limit must be > 0 seconds, got {self.time_limit:g}")
        from nowplan.experiments.faults import split_scenario

        spec = get_domain(self.domain)
        for s in self.scenarios:
            spec.scenario(split_scenario(s)[0])
        for st in self.strategies:
            parse_strategy(st)

    def probes(self, configs: list[RunConfig] | None = None) -> list[RunConfig]:
        """One configuration per (scenario, strategy) of ``configs`` (default: all), its first seed's:
        what :func:`~nowplan.experiments.precheck.check_runs` builds before a sweep runs."""
        first: dict[tuple[str, str], RunConfig] = {}
        for c in self.configs() if configs is None else configs:
            first.setdefault((c.scenario, c.strategy), c)
        return list(first.values())

    def check_runs(self, configs: list[RunConfig] | None = None) -> None:
        """Refuse (:class:`ScenarioError`, one line) a sweep one of whose runs would be refused at its
        start; see :mod:`nowplan.experiments.precheck`.  Runs domain code in a worker process."""
        from nowplan.experiments.precheck import check_runs
        from nowplan.experiments.runner import hard_limit

        probes = self.probes(configs)
        scenarios = len({c.scenario for c in probes})  # each built once, as a run's start would
        check_runs(probes, hard_limit(self.time_limit) * max(1, scenarios))

    def configs(self) -> list[RunConfig]:
        """Seeds outermost, so a partial sweep has every strategy on the first seeds."""
        return [
            RunConfig(self.domain, sc, st, seed, float(self.time_limit))
            for seed in self.seeds
            for sc in self.scenarios
            for st in self.strategies
        ]


class SweepState(enum.Enum):
    COMPLETE = "complete"  # every configuration has a record
    INCOMPLETE = "incomplete"  # stopped early (interrupted)


@dataclass
class SweepResult:
    spec: SweepSpec
    state: SweepState
    total: int  # configurations in the sweep
    already: int  # found in the store at the start
    ran: int  # run by this call
    records: list[RunRecord] = field(default_factory=list)  # this sweep's records in the store
    elapsed_s: float = 0.0

    def status_counts(self) -> Counter[str]:
        return Counter(r.status.value for r in self.records)

    def summary(self) -> str:
        header = ["scenario", "strategy", "runs", "reached", "failed", "limit", "livelock", "error",
                  "actions", "cost", "replans", "plan CPU s", "wall s"]
        rows: list[list[str]] = []
        for g in group_records(self.records):
            rows.append([
                g.key[1], g.key[2], str(len(g.records)),
                *(str(g.count(o)) for o in ("reached", "failed", "limit", "livelock", "error")),
                _mean(g.metric("actions")), _mean(g.metric("execution_cost")), _mean(g.metric("replans")),
                _mean(g.metric("planning_cpu_s")), _mean(g.metric("wall_s"), 2),
            ])
        head = (
            f"sweep {self.spec.domain}: {len(self.records)}/{self.total} runs stored "
            f"({self.already} already there, {self.ran} run now, {self.elapsed_s:.1f} s)"
        )
        if self.state is SweepState.INCOMPLETE:
            head += " — INCOMPLETE, run the same command again to resume"
        crashed = [r for r in self.records if r.status is RunStatus.CRASHED]
        tail = ""
        if crashed:
            tail = "\ncrashed runs (see 'error' in the store):\n" + "\n".join(
                f"  {r.config.label()}: {r.reason}" for r in crashed[:10]
            )
            if len(crashed) > 10:
                tail += f"\n  … and {len(crashed) - 10} more"
        return head + "\n" + text_table(header, rows) + tail


def _mean(e: Estimate, digits: int = 3) -> str:
    return "–" if e.n == 0 else f"{e.mean:.{digits}g}"


def run_sweep(
    spec: SweepSpec,
    store: Store,
    backend: Backend | None = None,
    *,
    retry_errors: bool = False,
    progress: bool = True,
    progress_file: TextIO | None = None,
    check: bool = True,
) -> SweepResult:
    """Run the configurations of ``spec`` missing from ``store``; see the module docstring.

    With ``check`` (the default), those configurations are first checked (:meth:`SweepSpec.check_runs`):
    a strategy or fault level their runs would refuse raises :class:`ScenarioError` before any run.
    """
    from tqdm import tqdm

    spec.validate()
    backend = backend or LocalBackend()
    configs = spec.configs()
    keep = {RunStatus.DONE, RunStatus.TIMEOUT} if retry_errors else None
    stored = store.keys(keep)
    todo = [c for c in configs if c.key not in stored]
    already = len(configs) - len(todo)
    if check:
        spec.check_runs(todo)
    log.info("sweep %s: %d configurations, %d stored, %d to run on %s",
             spec.domain, len(configs), already, len(todo), backend.name)
    t0 = time.perf_counter()
    counts: Counter[str] = Counter()
    bar = tqdm(
        total=len(configs), initial=already, unit="run", desc=f"sweep {spec.domain}",
        file=progress_file or sys.stderr, disable=not progress, dynamic_ncols=True, mininterval=0.25,
    )

    def on_record(rec: RunRecord) -> None:
        store.put(rec, replace=retry_errors)
        counts[rec.outcome] += 1
        bar.set_postfix({k: counts[k] for k in sorted(counts)}, refresh=False)
        bar.update(1)
        if rec.status is not RunStatus.DONE:
            log.info("run %s: %s (%s)", rec.config.label(), rec.status.value, rec.reason)

    state = SweepState.INCOMPLETE
    try:
        if todo:
            backend.run(todo, on_record)
        state = SweepState.COMPLETE
    except KeyboardInterrupt:
        log.warning("sweep interrupted; finished runs are stored, run the same command to resume")
    finally:
        bar.close()
    wanted = {c.key for c in configs}
    records = [r for r in store.records() if r.key in wanted]
    if len(records) != len(configs):
        state = SweepState.INCOMPLETE
    return SweepResult(spec, state, len(configs), already, sum(counts.values()), records,
                       time.perf_counter() - t0)


def make_backend(name: str, jobs: int | None = None, address: str | None = None) -> Backend:
    if name == "local":
        if address:
            raise ScenarioError("--address is for the Ray backend; add --backend ray")
        return LocalBackend(jobs)
    if name == "ray":
        from nowplan.experiments.ray_backend import RayBackend

        return RayBackend(jobs, address)
    raise ScenarioError(f"unknown backend '{name}'; valid backends: local, ray")
