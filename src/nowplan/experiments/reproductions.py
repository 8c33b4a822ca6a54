"""Reproductions of the seed papers' tables, declared by the domains that run them.

A domain that can reproduce a seed's table lists a :class:`Reproduction` in
its spec (``DomainSpec(reproductions=...)``), whose ``run`` function sweeps
its configurations (quick or full) and returns a
:class:`ReproductionResult` with rows shaped like the paper's
(:mod:`nowplan.experiments.papers`).  A seed no domain declares
gets an honest ``not_implemented`` result: no rows, the paper's numbers,
and a note saying what is missing.
"""

from __future__ import annotations

import enum
import logging
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from nowplan.errors import ScenarioError
from nowplan.experiments.papers import PAPERS, SeedPaper
from nowplan.experiments.report import Table, table
from nowplan.experiments.verdicts import Comparison

log = logging.getLogger(__name__)


class ReproStatus(enum.Enum):
    DONE = "done"
    NOT_IMPLEMENTED = "not_implemented"


@dataclass
class ReproductionResult:
    seed: str
    status: ReproStatus
    rows: list[dict[str, Any]] = field(default_factory=list)
    paper: list[dict[str, Any]] = field(default_factory=list)
    notes: str = ""
    title: str = ""
    outputs: list[Path] = field(default_factory=list)  # report files written, if any
    # the figures the reproduction is judged on: ours beside the paper's, met or not (verdicts.py)
    comparisons: list[Comparison] = field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        return {
            "seed": self.seed,
            "title": self.title,
            "status": self.status.value,
            "rows": self.rows,
            "paper": self.paper,
            "notes": self.notes,
            "verdicts": [{"what": c.quantity, "ours": c.ours, "paper": c.paper, "target": c.target,
                          "verdict": c.verdict.value} for c in self.comparisons],
        }


@dataclass(frozen=True)
class ReproductionOptions:
    quick: bool = False  # a small version: a few minutes on 2 cores (the CLI's default; --full clears it)
    out_dir: Path | None = None  # write a report (ours beside the paper's) here
    jobs: int | None = None
    # seeds 002 and 004 (others ignore these): package counts and trials per point (004: problems per
    # task), and a JSON-lines file
    # that keeps every finished run and lets a later call skip the runs it already holds
    sizes: tuple[int, ...] | None = None
    trials: int | None = None
    runs_file: Path | None = None
    stored_only: bool = False  # seed 002: summarise the runs in runs_file, run nothing
    easy: bool = False  # seed 004: the original (easy) kitchen problems instead of the hard distribution


ReproduceFn = Callable[[ReproductionOptions], ReproductionResult]


@dataclass(frozen=True)
class Reproduction:
    seed: str
    title: str
    run: ReproduceFn


def seeds() -> list[str]:
    return sorted(PAPERS)


def normalize_seed(text: str) -> str:
    s = text.strip()
    if s.isdigit():
        s = s.zfill(3)
    if s not in PAPERS:
        raise ScenarioError(f"unknown seed '{text}'; valid seeds: {', '.join(seeds())}")
    return s


def declared() -> dict[str, Reproduction]:
    """Every reproduction the domains' specs declare, by seed (two for one seed is an error)."""
    from nowplan.domains.registry import domain_names, get_domain

    try:
        names = domain_names()
    except ImportError as exc:  # a domain package still under construction must not hide the rest
        log.warning("could not load every domain package: %s", exc)
        return {}
    out: dict[str, Reproduction] = {}
    for name in names:
        for repro in get_domain(name).reproductions:
            seed = normalize_seed(repro.seed)
            if seed in out:
                raise ScenarioError(f"two domains declare a reproduction of seed {seed}; keep one")
            out[seed] = repro
    return out


def registered() -> list[str]:
    return sorted(declared())


def paper_of(seed: str) -> SeedPaper:
    return PAPERS[normalize_seed(seed)]


def reproduce(seed: str, options: ReproductionOptions | None = None) -> ReproductionResult:
    """Run the registered reproduction of ``seed``, or say plainly why there is none."""
    s = normalize_seed(seed)
    paper = PAPERS[s]
    repro = declared().get(s)
    if repro is None:
        return not_implemented(paper)
    opts = options or ReproductionOptions()
    result = repro.run(opts)
    if not result.paper:
        result.paper = [dict(r) for r in paper.rows]
    result.title = result.title or repro.title
    if opts.out_dir is not None and result.comparisons:
        from nowplan.experiments.verdicts import write

        result.outputs.extend(write(result.comparisons, result.title, opts.out_dir))
    return result


def missing_strategies(paper: SeedPaper) -> list[str]:
    from nowplan.acting.strategy import parse_strategy

    missing = []
    for name in paper.strategies:
        try:
            parse_strategy(name)
        except ScenarioError:
            missing.append(name)
    return missing


def not_implemented(paper: SeedPaper) -> ReproductionResult:
    missing = missing_strategies(paper)
    parts = [f"its domain ({paper.domain}) has not landed"]
    if missing:
        names = ", ".join(repr(m) for m in missing)
        parts.append(f"the strateg{'ies' if len(missing) > 1 else 'y'} {names} "
                     f"{'are' if len(missing) > 1 else 'is'} not implemented yet")
    note = (
        f"not yet implemented: the reproduction of seed {paper.seed} ({paper.system}) is not "
        f"registered: {'; '.join(parts)}. No rows are reported until it is. "
        f"Paper: {paper.notes}"
    )
    return ReproductionResult(
        seed=paper.seed,
        status=ReproStatus.NOT_IMPLEMENTED,
        rows=[],
        paper=[dict(r) for r in paper.rows],
        notes=note,
        title=f"seed {paper.seed}: {paper.system}",
    )


def side_by_side(
    rows: Sequence[dict[str, Any]], paper: Sequence[dict[str, Any]], labels: Sequence[str], caption: str = ""
) -> Table:
    """A report table with our value and the paper's for each label and metric column."""
    metrics = [k for r in [*rows, *paper] for k in r if k not in labels and k != "source"]
    metrics = list(dict.fromkeys(metrics))

    def key(r: dict[str, Any]) -> tuple[str, ...]:
        return tuple(str(r.get(c, "")) for c in labels)

    ours = {key(r): r for r in rows}
    theirs = {key(r): r for r in paper}
    header = [*labels, *(f"{m} ({who})" for m in metrics for who in ("ours", "paper"))]
    out = []
    for k in dict.fromkeys([*ours, *theirs]):
        a, b = ours.get(k, {}), theirs.get(k, {})
        out.append([*k, *(_fmt(src.get(m)) for m in metrics for src in (a, b))])
    return table(header, out, caption)


def _fmt(v: Any) -> str:
    if v is None:
        return "–"
    if isinstance(v, float):
        return f"{v:.3g}"
    return str(v)
