"""A reproduction's verdicts: each of its targets, ours beside the paper's figure, met or not.

A reproduction fills :attr:`ReproductionResult.comparisons` with one
:class:`Comparison` per figure it is judged on.  ``nowplan reproduce``
prints them as a markdown table (:func:`markdown_table`) and, with
``--out DIR``, writes the table to ``DIR/verdicts.md`` and a bar chart of
the figures that have a number on both sides to ``DIR/verdicts.png``.
"""

from __future__ import annotations

import enum
import math
import textwrap
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path


class Verdict(enum.Enum):
    MET = "met"
    NOT_MET = "not met"
    NO_PAPER_FIGURE = "no paper figure"  # nothing to compare with (and no target of our own)


@dataclass(frozen=True)
class Comparison:
    quantity: str  # what is compared, e.g. "cost decrease %, single origin and destination"
    ours: float | None
    paper: float | None  # None: the paper gives no figure
    verdict: Verdict
    target: str = ""  # how the verdict is judged, e.g. ">= paper" or "<= 0.7"
    ours_text: str = ""  # how to print ours, when more than the number (e.g. "27.3 ± 0.8")
    paper_text: str = ""

    def cells(self) -> list[str]:
        ours = self.ours_text or _num(self.ours)
        paper = self.paper_text or _num(self.paper)
        verdict = self.verdict.value
        if self.verdict is not Verdict.NO_PAPER_FIGURE and self.paper is None and paper.startswith("–"):
            verdict = f"no paper figure; our target {verdict}"  # judged on the project's target alone
        return [self.quantity, ours, paper, self.target or "–", verdict]


def judged(quantity: str, ours: float | None, paper: float | None, *, at_least: float | None = None,
           at_most: float | None = None, target: str = "", ours_text: str = "",
           paper_text: str = "") -> Comparison:
    """A comparison judged by a bound: ``ours >= at_least`` and/or ``ours <= at_most``.

    With no bound and no paper figure the verdict is ``no paper figure``; a
    missing ``ours`` (nothing measured) is ``not met``.
    """
    if at_least is None and at_most is None:
        verdict = Verdict.NO_PAPER_FIGURE
    elif ours is None or math.isnan(ours):
        verdict = Verdict.NOT_MET
    else:
        ok = (at_least is None or ours >= at_least - 1e-9) and (at_most is None or ours <= at_most + 1e-9)
        verdict = Verdict.MET if ok else Verdict.NOT_MET
    return Comparison(quantity, ours, paper, verdict, target, ours_text, paper_text)


def markdown_table(comparisons: Sequence[Comparison]) -> str:
    head = ["what", "ours", "paper", "target", "verdict"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    lines += ["| " + " | ".join(c.replace("|", "\\|") for c in cmp.cells()) + " |" for cmp in comparisons]
    return "\n".join(lines)


def tally(comparisons: Sequence[Comparison]) -> str:
    """``"3 met, 1 not met, 2 without a paper figure"``."""
    n = {v: sum(c.verdict is v for c in comparisons) for v in Verdict}
    parts = [f"{n[Verdict.MET]} met", f"{n[Verdict.NOT_MET]} not met"]
    if n[Verdict.NO_PAPER_FIGURE]:
        parts.append(f"{n[Verdict.NO_PAPER_FIGURE]} without a paper figure or target")
    return ", ".join(parts)


def write(comparisons: Sequence[Comparison], title: str, out_dir: Path) -> list[Path]:
    """``verdicts.md`` (the table) and, where figures exist on both sides, ``verdicts.png``."""
    out_dir.mkdir(parents=True, exist_ok=True)
    md = out_dir / "verdicts.md"
    paths = [md]
    both = [c for c in comparisons if c.ours is not None and c.paper is not None and not math.isnan(c.ours)]
    text = [f"# {title}", "", markdown_table(comparisons), "", tally(comparisons) + "."]
    if both:
        png = out_dir / "verdicts.png"
        _plot(both, title, png)
        paths.append(png)
        text += ["", "![ours beside the paper's](verdicts.png)"]
    md.write_text("\n".join(text) + "\n", encoding="utf-8")
    return paths


def _plot(comparisons: Sequence[Comparison], title: str, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # the quantities differ in kind and scale, so each bar is ours / the paper's, on a log axis
    pairs = [(c, float(c.ours or 0.0) / float(c.paper)) for c in comparisons if c.paper and (c.ours or 0) > 0]
    n = max(len(pairs), 1)
    fig, ax = plt.subplots(figsize=(7.5, 0.4 * n + 1.4))
    colours = {Verdict.MET: "#3a9d5d", Verdict.NOT_MET: "#d05050", Verdict.NO_PAPER_FIGURE: "#999999"}
    ratios = [r for _, r in pairs]
    # each bar runs from 1 (the paper's figure) to ours / the paper's, left or right of the line
    ax.barh(range(len(pairs)), [r - 1.0 for r in ratios], left=1.0, color=[colours[c.verdict] for c, _ in pairs])
    ax.axvline(1.0, color="black", linewidth=0.8)
    ax.set_xscale("log")
    span = max([abs(math.log10(r)) for r in ratios] + [0.05]) * 1.15
    ax.set_xlim(10 ** -span, 10 ** span)
    ax.set_yticks(list(range(len(pairs))))
    ax.set_yticklabels([f"{c.quantity} [{c.verdict.value}]" for c, _ in pairs], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("ours / paper's (log scale; 1 = the paper's figure)", fontsize=8)
    ax.set_title(textwrap.fill(title, 90), fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def _num(v: float | None) -> str:
    if v is None:
        return "–"
    if math.isnan(v):
        return "n/a"
    return f"{v:.3g}" if abs(v) < 1000 else f"{v:,.0f}"
