"""What each seed paper reports, transcribed from ``../shared/seeds/`` (no numbers of ours).

Rows use the same shape as a reproduction's rows: label columns first,
then metric columns.  Where a paper gives a number only in prose, the row
says so in its ``source`` column; where it gives none, there are no rows.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class SeedPaper:
    seed: str
    system: str  # the system the paper describes
    citation: str
    domain: str  # what the reproduction needs from a domain package
    strategies: tuple[str, ...]  # strategy switches the reproduction compares
    rows: tuple[dict[str, Any], ...] = field(default=())
    notes: str = ""


def _bhpn_rows() -> tuple[dict[str, Any], ...]:
    # seed 000, Table I: per domain and algorithm, mean picks/places, looks, moves and the
    # total simulated execution time as a ratio to the original BHPN's
    table: dict[str, list[tuple[float, float, float, float]]] = {
        "1": [(4.75, 4.25, 12, 1), (2.1, 3.2, 7.8, 1.01), (2, 3, 6.8, 0.57)],
        "2": [(3, 5, 11.8, 1), (2, 6.3, 11.1, 1.66), (2, 6.3, 10.7, 1.06)],
        "3": [(3, 6, 10.3, 1), (1, 5.8, 8, 1.40), (1, 5, 7, 0.89)],
        "Avg": [(3.6, 5.0, 11.4, 1), (1.7, 5.1, 9, 1.33), (1.7, 4.8, 8.1, 0.81)],
    }
    algorithms = ("original BHPN", "aggressive replanning", "selective replanning")
    rows = []
    for domain, values in table.items():
        for alg, (pp, looks, moves, ratio) in zip(algorithms, values, strict=True):
            rows.append({"domain": domain, "algorithm": alg, "picks_places": float(pp),
                         "looks": float(looks), "moves": float(moves), "time_ratio": float(ratio),
                         "source": "Table I"})
    return tuple(rows)


def _ssreplan_rows() -> tuple[dict[str, Any], ...]:
    # seed 004, Table I: success rate (%) and mean total planning time (s) of successful trials
    table: dict[str, list[tuple[float, float]]] = {
        "Inspect": [(96, 41), (100, 45), (100, 32), (100, 26)],
        "Stow": [(80, 124), (88, 226), (88, 92), (88, 108)],
        "Swap": [(52, 190), (40, 484), (60, 105), (80, 232)],
        "Cook": [(20, 375), (40, 406), (56, 249), (100, 203)],
    }
    algorithms = ("neither", "constraints", "deferred", "both")
    rows = []
    for task, values in table.items():
        for alg, (pct, t) in zip(algorithms, values, strict=True):
            rows.append({"task": task, "algorithm": alg, "success_pct": float(pct),
                         "planning_time_s": float(t), "source": "Table I"})
    return tuple(rows)


PAPERS: dict[str, SeedPaper] = {
    "000": SeedPaper(
        seed="000",
        system="BHPN with reconsideration and foresight",
        citation="Levihn, Kaelbling, Lozano-Pérez, Stilman: Foresight and Reconsideration in "
        "Hierarchical Planning and Execution",
        domain="NAMO (navigation among movable obstacles) with unknown obstacles, 3 maps",
        strategies=("hpn", "aggressive", "selective"),
        rows=_bhpn_rows(),
        notes="Table I averages 137 runs over three simulated NAMO domains; time is relative to "
        "the original BHPN (domain 1 = 1265 s, 2 = 1020 s, 3 = 850 s, average 1045 s).",
    ),
    "002": SeedPaper(
        seed="002",
        system="RCHPN (dynamic peephole optimization)",
        citation="Hadfield-Menell, Kaelbling, Lozano-Pérez: Optimization in the Now: Dynamic "
        "Peephole Optimization for Hierarchical Planning",
        domain="marsupial logistics (trucks and a plane whose cargo holds are grids with a loader robot)",
        strategies=("hpn", "peephole"),
        rows=(
            {"regime": "single origin, single destination", "cost_decrease_pct": 30.0,
             "source": "Sec. V-B text ('an average of 30% improvement')"},
            {"regime": "origin or destination dispersed", "cost_decrease_pct": 15.0,
             "source": "Sec. V-B text ('about 15%')"},
            {"regime": "multiple origins, multiple destinations", "cost_decrease_pct": 5.0,
             "source": "Sec. V-B text ('5% improvement')"},
        ),
        notes="Percent decrease in execution cost of RCHPN relative to HPN, averaged over 3 to 10 "
        "packages and 10 trials each; the per-size values exist only as a plot (Fig. 3), so the rows "
        "are the rounded numbers the text states.",
    ),
    "003": SeedPaper(
        seed="003",
        system="vision-guided planning/replanning framework",
        citation="Yıldırım, Tunalı: A Proposal for a Robotic Planning/Replanning Framework",
        domain="shuffled pieces on a grid seen by a camera (cells, recognised labels)",
        strategies=("hpn", "monitor"),
        rows=(),
        notes="The paper describes the framework and its control rules but reports no numeric "
        "results, so there is nothing to compare with.",
    ),
    "004": SeedPaper(
        seed="004",
        system="SS-Replan (online replanning in belief space)",
        citation="Garrett, Paxton, Lozano-Pérez, Kaelbling, Fox: Online Replanning in Belief Space "
        "for Partially Observable Task and Motion Problems",
        domain="kitchen tasks Inspect, Stow, Swap and Cook with drawers and occlusion",
        strategies=("reuse", "deferred"),
        rows=_ssreplan_rows(),
        notes="Table I: 25 generated problems per task, each policy limited to 10 minutes of total "
        "planning time; time is the mean over successful trials only.",
    ),
}
