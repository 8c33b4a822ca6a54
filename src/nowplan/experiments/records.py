"""Run configurations and run records.

A *run* is one (domain, scenario, seed, strategy, time limit) configuration
executed once.  Its :class:`RunRecord` carries the configuration, the
outcome with its reason, the metrics summary of the engine
(:meth:`nowplan.acting.metrics.Metrics.to_dict`), the wall time and the
nowplan version that produced it.  Records are keyed by a hash of the
configuration (:attr:`RunConfig.key`), which is what makes sweeps resumable.
"""

from __future__ import annotations

import enum
import hashlib
import json
import platform
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

from nowplan import __version__

# bump only if the meaning of a configuration changes; it salts every key
KEY_SALT = "nowplan-run-config-v1"

# metrics fields that depend on the machine's speed, not on the run's decisions
TIMING_FIELDS = ("planning_cpu_s", "wall_s")


class RunStatus(enum.Enum):
    """How a run ended, as seen by the sweep (not the planner's outcome)."""

    DONE = "done"  # the engine returned its metrics (outcome reached / failed / limit)
    CRASHED = "crashed"  # the run raised or its worker died; ``error`` has the text
    TIMEOUT = "timeout"  # the worker was killed after the hard time limit


# the ``outcome`` column: the engine's outcomes plus "error" for crashed runs
OUTCOMES = ("reached", "failed", "limit", "livelock", "error")


@dataclass(frozen=True)
class RunConfig:
    domain: str
    scenario: str
    strategy: str
    seed: int
    time_limit: float

    def to_dict(self) -> dict[str, Any]:
        return {
            "domain": self.domain,
            "scenario": self.scenario,
            "strategy": self.strategy,
            "seed": int(self.seed),
            "time_limit": float(self.time_limit),
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> RunConfig:
        return cls(
            str(d["domain"]), str(d["scenario"]), str(d["strategy"]), int(d["seed"]), float(d["time_limit"])
        )

    @property
    def key(self) -> str:
        """A stable hash of the configuration (same on every machine and version)."""
        canon = json.dumps({"salt": KEY_SALT, **self.to_dict()}, sort_keys=True, separators=(",", ":"))
        return hashlib.sha256(canon.encode("utf-8")).hexdigest()[:32]

    def label(self) -> str:
        return f"{self.domain}/{self.scenario} {self.strategy} seed={self.seed}"


def now_iso() -> str:
    return datetime.now(UTC).isoformat(timespec="seconds")


@dataclass
class RunRecord:
    config: RunConfig
    status: RunStatus
    outcome: str  # one of OUTCOMES
    reason: str = ""
    metrics: dict[str, Any] = field(default_factory=dict)
    error: str | None = None  # exception text and traceback for crashed runs
    wall_s: float = 0.0  # whole run, scenario construction included, as measured by the worker
    version: str = __version__
    host: str = field(default_factory=platform.node)
    finished_at: str = field(default_factory=now_iso)

    @property
    def key(self) -> str:
        return self.config.key

    def to_dict(self) -> dict[str, Any]:
        return {
            "key": self.key,
            **self.config.to_dict(),
            "status": self.status.value,
            "outcome": self.outcome,
            "reason": self.reason,
            "metrics": self.metrics,
            "error": self.error,
            "wall_s": round(self.wall_s, 6),
            "version": self.version,
            "host": self.host,
            "finished_at": self.finished_at,
        }

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> RunRecord:
        return cls(
            config=RunConfig.from_dict(d),
            status=RunStatus(d["status"]),
            outcome=str(d["outcome"]),
            reason=str(d.get("reason") or ""),
            metrics=dict(d.get("metrics") or {}),
            error=d.get("error"),
            wall_s=float(d.get("wall_s") or 0.0),
            version=str(d.get("version") or ""),
            host=str(d.get("host") or ""),
            finished_at=str(d.get("finished_at") or ""),
        )

    def decisions(self) -> dict[str, Any]:
        """The record without machine-dependent fields: equal for equal runs anywhere."""
        m = {k: v for k, v in self.metrics.items() if k not in TIMING_FIELDS}
        return {"key": self.key, "status": self.status.value, "outcome": self.outcome,
                "reason": self.reason if self.status is RunStatus.DONE else "", "metrics": m}


def crashed(config: RunConfig, error: str, reason: str, wall_s: float = 0.0) -> RunRecord:
    return RunRecord(config, RunStatus.CRASHED, "error", reason=reason, error=error, wall_s=wall_s)


def timed_out(config: RunConfig, limit: float, wall_s: float) -> RunRecord:
    return RunRecord(
        config,
        RunStatus.TIMEOUT,
        "limit",
        reason=f"killed after exceeding the time limit of {config.time_limit:g} s (hard limit {limit:g} s)",
        wall_s=wall_s,
    )
