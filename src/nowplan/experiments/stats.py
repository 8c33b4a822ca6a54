"""Grouping run records and summarising them: counts, mean ± standard error, tables."""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from nowplan.experiments.records import OUTCOMES, RunRecord, RunStatus

# metrics summarised for every group, in table order, with their headings
METRICS: tuple[tuple[str, str], ...] = (
    ("actions", "actions"),
    ("execution_cost", "execution cost"),
    ("plans_made", "plans made"),
    ("replans", "replans"),
    ("plan_failures", "planner failures"),
    ("planning_cpu_s", "planning CPU (s)"),
    ("wall_s", "wall (s)"),
)

GroupKey = tuple[str, str, str]  # (domain, scenario, strategy)


@dataclass(frozen=True)
class Estimate:
    n: int
    mean: float
    se: float  # standard error of the mean (sample sd / sqrt(n)); nan if n < 2

    def fmt(self, digits: int = 3) -> str:
        if self.n == 0:
            return "–"
        m = f"{self.mean:.{digits}g}"
        return m if math.isnan(self.se) else f"{m} ± {self.se:.2g}"


def estimate(values: Sequence[float]) -> Estimate:
    n = len(values)
    if n == 0:
        return Estimate(0, math.nan, math.nan)
    mean = math.fsum(values) / n
    if n < 2:
        return Estimate(n, mean, math.nan)
    var = math.fsum((v - mean) ** 2 for v in values) / (n - 1)
    return Estimate(n, mean, math.sqrt(var / n))


@dataclass
class Group:
    key: GroupKey
    records: list[RunRecord] = field(default_factory=list)

    @property
    def label(self) -> str:
        return " / ".join(self.key)

    def count(self, outcome: str) -> int:
        return sum(1 for r in self.records if r.outcome == outcome)

    @property
    def completed(self) -> list[RunRecord]:
        """Runs that returned metrics (whatever their outcome)."""
        return [r for r in self.records if r.status is RunStatus.DONE]

    def metric(self, name: str) -> Estimate:
        return estimate([float(r.metrics.get(name, 0.0) or 0.0) for r in self.completed])

    def action_types(self) -> list[str]:
        names: set[str] = set()
        for r in self.completed:
            names.update(r.metrics.get("action_counts", {}) or {})
        return sorted(names)

    def action_count(self, name: str) -> Estimate:
        return estimate([float((r.metrics.get("action_counts") or {}).get(name, 0)) for r in self.completed])

    def seeds(self) -> list[int]:
        return sorted({r.config.seed for r in self.records})


def group_records(records: Iterable[RunRecord]) -> list[Group]:
    groups: dict[GroupKey, Group] = {}
    for r in records:
        k = (r.config.domain, r.config.scenario, r.config.strategy)
        groups.setdefault(k, Group(k)).records.append(r)
    return [groups[k] for k in sorted(groups)]


def seeds_text(seeds: Sequence[int]) -> str:
    """``[0, 1, 2, 5]`` -> ``"0-2,5"``."""
    out: list[str] = []
    i = 0
    s = sorted(seeds)
    while i < len(s):
        j = i
        while j + 1 < len(s) and s[j + 1] == s[j] + 1:
            j += 1
        out.append(str(s[i]) if i == j else f"{s[i]}-{s[j]}")
        i = j + 1
    return ",".join(out)


# -- tables -----------------------------------------------------------------------------


def outcome_rows(groups: Sequence[Group]) -> tuple[list[str], list[list[str]]]:
    header = ["domain", "scenario", "strategy", "runs", *OUTCOMES, "seeds"]
    rows = [
        [*g.key, str(len(g.records)), *(str(g.count(o)) for o in OUTCOMES), seeds_text(g.seeds())]
        for g in groups
    ]
    return header, rows


def metric_rows(groups: Sequence[Group]) -> tuple[list[str], list[list[str]]]:
    header = ["domain", "scenario", "strategy", "n", *(h for _, h in METRICS)]
    rows = [[*g.key, str(len(g.completed)), *(g.metric(m).fmt() for m, _ in METRICS)] for g in groups]
    return header, rows


def action_rows(groups: Sequence[Group]) -> tuple[list[str], list[list[str]]]:
    names = sorted({a for g in groups for a in g.action_types()})
    header = ["domain", "scenario", "strategy", "n", *names]
    rows = [[*g.key, str(len(g.completed)), *(g.action_count(a).fmt() for a in names)] for g in groups]
    return header, rows


def markdown_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    def cell(s: str) -> str:
        return s.replace("|", "\\|").replace("\n", " ")

    lines = ["| " + " | ".join(cell(h) for h in header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(cell(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def text_table(header: Sequence[str], rows: Sequence[Sequence[str]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(header)]
    fmt = "  ".join(f"{{:<{w}}}" for w in widths)
    lines = [fmt.format(*header), "  ".join("-" * w for w in widths)]
    lines += [fmt.format(*row) for row in rows]
    return "\n".join(line.rstrip() for line in lines)
