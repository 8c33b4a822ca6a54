"""The anytime improvement's parts, in-process, on benchmarks/classical's instances (issue 19, target 1).

For every instance: ground, run LAMA's first iteration and action elimination, then
improve that plan with each strategy for the budget `nowplan plan --improve 1` gives
(the first search's expansions plus forward.IMPROVE_BASE work units, planning/anytime.py), and print its cost against
lama-first's cost stored in a `benchmarks/classical.py` CSV:

* ``wastar``: the weighted A* searches alone (weights 5, 3, 2, 1; what
  `nowplan plan` ran before the neighborhood search),
* ``pngs``: plan neighborhood graph search alone,
* ``default``: anytime.improve, what `nowplan plan` runs (weighted A* for
  anytime.WASTAR_SHARE of the budget, then the neighborhood search).

    PYTHONPATH=src .venv/bin/python benchmarks/classical_improve.py [--domains barman]
        [--fd-csv benchmarks/results/classical_orders/classical.csv]

Work budgets (counted states), so the figures do not depend on the machine's load.
"""

from __future__ import annotations

import argparse
import csv
import sys
from collections.abc import Callable
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks.classical.generate import DOMAINS, domain_file, instance_files  # noqa: E402
from nowplan.core.levels import flat_levels  # noqa: E402
from nowplan.io.pddl_read import load_pddl  # noqa: E402
from nowplan.planning import anytime, pngs  # noqa: E402
from nowplan.planning.forward import IMPROVE_BASE, search  # noqa: E402
from nowplan.planning.hff import RelaxedHeuristic  # noqa: E402
from nowplan.planning.postprocess import eliminate_actions  # noqa: E402
from nowplan.planning.task import Task, build_task  # noqa: E402

STRATEGIES = ("wastar", "pngs", "default")


def _wastar_only(task: Task, plan: list[int], budget: int, branching: int) -> list[int]:
    return anytime.improve(task, plan, budget, wastar_share=1.0, branching=branching)


def _pngs_only(task: Task, plan: list[int], budget: int, branching: int) -> list[int]:
    spent = [0]

    def stop() -> bool:
        spent[0] += anytime.PNGS_UNITS
        return spent[0] > budget

    return pngs.improve_by_neighborhood(task, plan, stop, RelaxedHeuristic(task).native)


RUN: dict[str, Callable[[Task, list[int], int, int], list[int]]] = {
    "wastar": _wastar_only, "pngs": _pngs_only,
    "default": lambda t, p, b, k: anytime.improve(t, p, b, branching=k)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--domains", default=",".join(DOMAINS))
    ap.add_argument("--fd-csv", default=str(ROOT / "benchmarks/results/classical_orders/classical.csv"))
    args = ap.parse_args()
    fd = {(r["domain"], r["instance"]): float(r["cost"]) for r in csv.DictReader(open(args.fd_csv))
          if r["planner"] == "fd-lama-first" and r["cost"]}
    ratios: dict[str, list[float]] = {s: [] for s in STRATEGIES}
    for d in args.domains.split(","):
        for prob in instance_files(d):
            key = (d, prob.stem)
            if key not in fd:
                continue
            p = load_pddl(str(domain_file(d)), str(prob))
            task = build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a, p=p: a.cost(p.init))
            res = search(task, method="lama")
            if res.actions is None:
                print(f"{d} {prob.stem}: no first plan ({res.status.value})")
                continue
            ids = {a: i for i, a in enumerate(task.actions)}
            first = eliminate_actions(task, [ids[a] for a in res.actions])
            budget = res.expanded + IMPROVE_BASE  # what `nowplan plan --improve 1` gives (forward.py)
            branching = max(1, round(res.generated / max(1, res.expanded)))
            line = f"{d:11s} {prob.stem} lama-first {fd[key]:4.0f} first {sum(task.cost[a] for a in first):4.0f}"
            for s in STRATEGIES:
                c = sum(task.cost[a] for a in RUN[s](task, first, budget, branching))
                ratios[s].append(c / fd[key])
                line += f" | {s} {c:4.0f} ({c / fd[key]:.3f})"
            print(line, flush=True)
    for s, rs in ratios.items():
        if rs:
            print(f"{s:8s} within 10 % of lama-first: {sum(r <= 1.1 for r in rs)} of {len(rs)}, "
                  f"mean ratio {sum(rs) / len(rs):.3f}, worst {max(rs):.3f}")


if __name__ == "__main__":
    main()
