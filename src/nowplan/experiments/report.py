"""Reports from stored runs: markdown plus one self-contained HTML page.

A report is a list of blocks (headings, paragraphs, tables, figures) built
from run records; :func:`write_report` renders it twice: ``report.md``
(figures saved next to it as PNG files) and ``report.html`` (the same
figures inlined as base64, no external resources).  Reproductions add
their own blocks, e.g. the paper's numbers beside ours.
"""

from __future__ import annotations

import base64
import html
import io
import logging
import platform
import sys
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

from nowplan import __version__
from nowplan.errors import NowplanError, StoreError
from nowplan.experiments.records import OUTCOMES, RunRecord, RunStatus, now_iso
from nowplan.experiments.stats import (
    Group,
    action_rows,
    group_records,
    markdown_table,
    metric_rows,
    outcome_rows,
)

log = logging.getLogger(__name__)

# metrics plotted per (domain, scenario), one panel each
PLOTTED = (
    ("execution_cost", "execution cost"),
    ("actions", "actions"),
    ("planning_cpu_s", "planning CPU time (s)"),
    ("replans", "replans"),
)
OUTCOME_COLOURS = {"reached": "#4c9a5b", "failed": "#c8553d", "limit": "#e0a458", "livelock": "#8e6c8a", "error": "#6c6c6c"}


@dataclass(frozen=True)
class Heading:
    text: str
    level: int = 2


@dataclass(frozen=True)
class Paragraph:
    text: str


@dataclass(frozen=True)
class Table:
    header: tuple[str, ...]
    rows: tuple[tuple[str, ...], ...]
    caption: str = ""


@dataclass(frozen=True)
class Image:
    name: str  # file stem, e.g. "logistics-small"
    caption: str
    png: bytes = field(repr=False)


Block = Heading | Paragraph | Table | Image


@dataclass(frozen=True)
class ReportFiles:
    markdown: Path
    html: Path
    images: tuple[Path, ...]


def table(header: Sequence[str], rows: Sequence[Sequence[str]], caption: str = "") -> Table:
    return Table(tuple(header), tuple(tuple(r) for r in rows), caption)


# -- building ---------------------------------------------------------------------------


def build_report(records: Sequence[RunRecord], title: str, source: str = "") -> list[Block]:
    """The standard report of a set of runs (one table set, one figure per domain/scenario)."""
    if not records:
        raise StoreError(f"{source or 'the store'} holds no runs; run 'nowplan sweep' first")
    groups = group_records(records)
    versions = sorted({r.version for r in records})
    hosts = sorted({r.host for r in records})
    limits = sorted({r.config.time_limit for r in records})
    blocks: list[Block] = [
        Heading(title, 1),
        Paragraph(
            f"{len(records)} runs from {source or 'a run store'}, in {len(groups)} groups of "
            f"domain / scenario / strategy; produced by nowplan {', '.join(versions)} on "
            f"{', '.join(hosts)}; time limit per run {', '.join(f'{t:g}' for t in limits)} s. "
            f"Report generated {now_iso()} by nowplan {__version__} "
            f"(Python {sys.version.split()[0]}, {platform.platform(terse=True)})."
        ),
        Heading("Outcomes"),
        table(*outcome_rows(groups), caption="Runs per outcome; 'error' counts runs that crashed."),
        Heading("Metrics"),
        table(
            *metric_rows(groups),
            caption="Mean ± standard error over the n runs that returned metrics (crashed and "
            "killed runs have none).",
        ),
        Heading("Actions per type"),
        table(*action_rows(groups), caption="Mean ± standard error of primitive actions of each type."),
    ]
    blocks += _problem_runs(records)
    blocks.append(Heading("Plots"))
    by_scenario: dict[tuple[str, str], list[Group]] = {}
    for g in groups:
        by_scenario.setdefault((g.key[0], g.key[1]), []).append(g)
    for (domain, scenario), gs in by_scenario.items():
        blocks.append(
            Image(
                _slug(f"{domain}-{scenario}"),
                f"{domain} / {scenario}: mean ± standard error per strategy, and outcomes.",
                plot_groups(gs, f"{domain} / {scenario}"),
            )
        )
    return blocks


def _problem_runs(records: Sequence[RunRecord], limit: int = 30) -> list[Block]:
    bad = [r for r in records if r.status is not RunStatus.DONE]
    if not bad:
        return []
    rows = [(r.config.label(), r.status.value, r.reason) for r in bad[:limit]]
    more = f" (first {limit} of {len(bad)})" if len(bad) > limit else ""
    return [
        Heading("Crashed or killed runs"),
        table(("run", "status", "reason"), rows, caption=f"Runs without metrics{more}; "
              "the full exception text is in the store's 'error' column."),
    ]


def _slug(text: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in text)


def plot_groups(groups: Sequence[Group], title: str) -> bytes:
    """One PNG: a bar panel per metric (error bars = standard error) and an outcome panel."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    names = [g.key[2] for g in groups]
    x = list(range(len(groups)))
    fig = Figure(figsize=(3.0 * (len(PLOTTED) + 1), 3.4), dpi=100, layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, len(PLOTTED) + 1)
    for ax, (metric, label) in zip(axes, PLOTTED, strict=False):
        est = [g.metric(metric) for g in groups]
        means = [e.mean if e.n else 0.0 for e in est]
        errs = [e.se if e.n > 1 else 0.0 for e in est]
        ax.bar(x, means, yerr=errs, capsize=4, color="#5b8cc0", edgecolor="#2d4f73")
        ax.set_title(label, fontsize=10)
        ax.set_xticks(x, names, rotation=30, ha="right", fontsize=8)
        ax.tick_params(axis="y", labelsize=8)
    ax = axes[-1]
    bottom = [0.0] * len(groups)
    for outcome in OUTCOMES:
        counts = [float(g.count(outcome)) for g in groups]
        if any(counts):
            ax.bar(x, counts, bottom=bottom, label=outcome, color=OUTCOME_COLOURS[outcome])
            bottom = [b + c for b, c in zip(bottom, counts, strict=True)]
    ax.set_title("outcomes (runs)", fontsize=10)
    ax.set_xticks(x, names, rotation=30, ha="right", fontsize=8)
    ax.tick_params(axis="y", labelsize=8)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.0, 1.0))
    fig.suptitle(title, fontsize=11)
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


# -- rendering --------------------------------------------------------------------------


def render_markdown(blocks: Sequence[Block]) -> str:
    out: list[str] = []
    for b in blocks:
        if isinstance(b, Heading):
            out.append("#" * b.level + " " + b.text)
        elif isinstance(b, Paragraph):
            out.append(b.text)
        elif isinstance(b, Table):
            out.append(markdown_table(b.header, b.rows))
            if b.caption:
                out.append(f"*{b.caption}*")
        else:
            out.append(f"![{b.caption}]({b.name}.png)\n\n*{b.caption}*")
    return "\n\n".join(out) + "\n"


_CSS = """
body{font-family:system-ui,-apple-system,'Segoe UI',sans-serif;margin:2rem auto;max-width:75rem;
padding:0 1rem;color:#222;line-height:1.45}
table{border-collapse:collapse;margin:.5rem 0;font-size:.9rem}
th,td{border:1px solid #ccc;padding:.25rem .6rem;text-align:right}
th{background:#eef2f7}td:nth-child(-n+3),th:nth-child(-n+3){text-align:left}
caption{caption-side:bottom;text-align:left;font-size:.85rem;color:#555;padding-top:.3rem}
figure{margin:1rem 0}img{max-width:100%}figcaption{font-size:.85rem;color:#555}
"""


def render_html(blocks: Sequence[Block]) -> str:
    esc = html.escape
    title = next((b.text for b in blocks if isinstance(b, Heading)), "nowplan report")
    out = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        f"<title>{esc(title)}</title><style>{_CSS}</style></head><body>",
    ]
    for b in blocks:
        if isinstance(b, Heading):
            lvl = min(max(b.level, 1), 6)
            out.append(f"<h{lvl}>{esc(b.text)}</h{lvl}>")
        elif isinstance(b, Paragraph):
            out.append(f"<p>{esc(b.text)}</p>")
        elif isinstance(b, Table):
            out.append("<table>")
            if b.caption:
                out.append(f"<caption>{esc(b.caption)}</caption>")
            out.append("<thead><tr>" + "".join(f"<th>{esc(h)}</th>" for h in b.header) + "</tr></thead>")
            out.append("<tbody>")
            for row in b.rows:
                out.append("<tr>" + "".join(f"<td>{esc(c)}</td>" for c in row) + "</tr>")
            out.append("</tbody></table>")
        else:
            data = base64.b64encode(b.png).decode("ascii")
            out.append(
                f'<figure><img alt="{esc(b.caption)}" src="data:image/png;base64,{data}">'
                f"<figcaption>{esc(b.caption)}</figcaption></figure>"
            )
    out.append("</body></html>")
    return "\n".join(out) + "\n"


def write_report(blocks: Sequence[Block], out_dir: str | Path) -> ReportFiles:
    """Write ``report.md`` (+ PNG files) and a self-contained ``report.html`` into ``out_dir``."""
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise NowplanError(f"{out}: exists and is not a directory; give -o a directory")
    out.mkdir(parents=True, exist_ok=True)
    images: list[Path] = []
    for b in blocks:
        if isinstance(b, Image):
            p = out / f"{b.name}.png"
            p.write_bytes(b.png)
            images.append(p)
    md = out / "report.md"
    md.write_text(render_markdown(blocks), encoding="utf-8")
    page = out / "report.html"
    page.write_text(render_html(blocks), encoding="utf-8")
    log.info("wrote %s, %s and %d images", md, page, len(images))
    return ReportFiles(md, page, tuple(images))


def report_store(store_path: str | Path, out_dir: str | Path, title: str | None = None) -> ReportFiles:
    """``nowplan report``: the standard report of every run in a store."""
    from nowplan.experiments.store import Store

    with Store(store_path, create=False) as store:
        records = store.records()
    blocks = build_report(records, title or f"nowplan report: {Path(store_path).name}", str(store_path))
    return write_report(blocks, out_dir)
