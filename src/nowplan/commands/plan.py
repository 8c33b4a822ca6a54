"""``nowplan plan DOMAIN.pddl PROBLEM.pddl``: a classical plan for a PDDL problem.

Prints the plan one action per line in PDDL syntax, or a JSON document with
``--json``.  By default the plan is *flat and concrete* (every precondition
counts) whatever the criticality file says: criticalities only matter to the
hierarchical executive.  ``--level top`` (or a number) plans at an
abstraction level instead, to inspect what the executive's first plan would
look like.  Exit status: 0 solved, 1 no plan (unsolvable or a limit
reached), 2 bad input.
"""

from __future__ import annotations

import argparse
import json
import logging
import sys
import time
from typing import Any

from nowplan.core.levels import LevelMap, flat_levels
from nowplan.commands.common import positive_float, positive_int
from nowplan.errors import UsageError

log = logging.getLogger(__name__)

ENGINES = ("nowplan", "forward", "regression", "fd")
# default expansion budgets: the forward search's is far beyond what a time limit of minutes allows (it
# expands ~10^5 states/s at most here; ~140 bytes a state), so that the time limit ends it, as FD's does
REGRESSION_NODES, FORWARD_NODES = 500_000, 20_000_000
SEARCHES = {
    "forward:gbfs": "lazy greedy best-first search, h_FF with preferred operators",
    "forward:astar": "weighted A* forward, h_FF",
    "forward:lama": "lazy greedy best-first search, h_FF and landmark count with preferred operators",
    "full": "regression A*",
    "serialization": "regression A*, serialization shortcut",
    "monotonic": "regression A*, monotonic shortcut",
}


def _level(value: str) -> str | int:
    if value in ("flat", "top"):
        return value
    try:
        return int(value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected 'flat', 'top' or a number, got '{value}'") from None


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "plan",
        help="find a plan for a PDDL domain and problem",
        description=__doc__.split("\n\n", 1)[1] if __doc__ else None,
    )
    p.add_argument("domain", metavar="DOMAIN.pddl", help="PDDL domain file")
    p.add_argument("problem", metavar="PROBLEM.pddl", help="PDDL problem file")
    p.add_argument("--criticality", metavar="FILE|auto",
                   help="criticality side file, or 'auto' to derive one from the domain (see docs/pddl.md)")
    p.add_argument("--engine", choices=ENGINES, default="nowplan",
                   help="nowplan (default): the executive's own planner, forward search where it applies "
                        "(PDDL always), else regression; forward | regression: force one; "
                        "fd: Fast Downward (needs the 'fd' extra)")
    p.add_argument("--search", choices=("gbfs", "lama", "astar"), default="lama",
                   help="forward search: lama (LAMA's first iteration: lazy greedy best-first on h_FF and "
                        "the landmark count with preferred operators; default), gbfs (the same on h_FF "
                        "alone, or on --heuristic) or astar (weighted by --weight; --weight 1 with "
                        "--heuristic max is optimal)")
    p.add_argument("--improve", type=float, default=1.0, metavar="K",
                   help="after the first forward plan, look for cheaper ones (weighted A* with falling "
                        "weights, then plan neighborhood search) for K times the first search's work plus "
                        "a fixed amount, counted in states, not seconds, so the plan does not depend on the "
                        "machine's load (default 1, 0 = off)")
    p.add_argument("--heuristic", choices=("ff", "add", "max"), default="ff",
                   help="heuristic of --search gbfs and astar: h_FF (default), h_add or h_max "
                        "(lama always uses h_FF and the landmark count)")
    p.add_argument("--cost-type", choices=("one", "plusone", "normal"), default="plusone",
                   help="action costs as the forward heuristics see them (FD's adapt_costs): plusone (cost + 1; "
                        "default), one (unit costs, as Fast Downward's lama-first, often faster and dearer "
                        "where costs differ) or normal")
    p.add_argument("--level", type=_level, default="flat",
                   help="'flat' (default: a concrete plan), 'top' (the most abstract level) or a number")
    p.add_argument("--json", action="store_true", help="print a JSON document instead of the plan")
    p.add_argument("--seed", type=int, default=0, help="seed for the planner's random choices (default 0)")
    p.add_argument("--time-limit", type=positive_float, default=60.0, metavar="S",
                   help="wall-clock limit in seconds (default 60)")
    p.add_argument("--max-nodes", type=positive_int, default=None, metavar="N",
                   help=f"node expansions allowed to the search (default: {REGRESSION_NODES} for the "
                        f"regression search; {FORWARD_NODES} for the forward search, which the time limit "
                        "ends first)")
    p.add_argument("--weight", type=positive_float, default=2.0, metavar="W",
                   help="weighted A*: f = g + W*h (regression engine and --search astar; default 2, 1 = A*)")
    p.add_argument("--shortcuts", action="store_true",
                   help="try HPN's serialization and monotonic shortcuts before full search")
    p.add_argument("--no-mutexes", action="store_true",
                   help="do not infer mutex invariants nor h2 mutex pairs (planning/h2.py): slower "
                        "regression; for comparisons")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from nowplan.io.pddl_read import load_pddl

    if args.search == "lama" and args.heuristic != "ff":
        raise UsageError(f"--heuristic {args.heuristic} applies to --search gbfs or astar; "
                         "--search lama (the default) uses h_FF and the landmark count")
    problem = load_pddl(args.domain, args.problem, args.criticality, mutexes=not args.no_mutexes)
    domain = problem.domain
    level: int | None
    if args.level == "flat":
        level = None
    elif args.level == "top":
        level = domain.top_level
    else:
        level = int(args.level)
        if not 0 <= level <= domain.top_level:
            raise UsageError(
                f"--level {level} is out of range: this domain's levels are 0..{domain.top_level}"
                " (or 'flat')"
            )
    t0 = time.perf_counter()
    c0 = time.process_time()
    if args.engine == "fd":
        from nowplan.planning.fd import solve_fd

        result = solve_fd(problem, level, time_limit=args.time_limit)
    else:
        from nowplan.planning.regression import PlannerConfig, plan

        config = PlannerConfig(
            engine="auto" if args.engine == "nowplan" else args.engine,
            search=args.search,
            forward_heuristic=args.heuristic,
            cost_type=args.cost_type,
            improve=args.improve,
            max_nodes=REGRESSION_NODES if args.max_nodes is None else args.max_nodes,
            forward_max_nodes=FORWARD_NODES if args.max_nodes is None else args.max_nodes,
            time_limit=args.time_limit,
            weight=args.weight,
            serialization=args.shortcuts,
            monotonic=args.shortcuts,
            seed=args.seed,
            h2=not args.no_mutexes,  # (the regression engine's: subgoals no reachable state holds dropped)
        )
        levels = flat_levels() if level is None else LevelMap(level)
        result = plan(domain, problem.objects, problem.init, problem.goal, levels, config)
    elapsed = time.perf_counter() - t0
    cpu = time.process_time() - c0
    # auxiliary operators (reaching a disjunctive goal) print as "" and are left out
    actions = [s for s in (a.pddl() for a in result.plan.actions) if s] if result.plan is not None else []
    if args.json:
        doc: dict[str, Any] = {
            "plan": actions,
            "cost": result.plan.cost(problem.init) if result.plan is not None else None,
            "status": result.status.value,
            "planning_time_s": round(elapsed, 6),
            "planning_cpu_s": round(cpu, 6),  # this process's CPU in the planner call (parse excluded)
            "method": f"fd:{result.method}" if args.engine == "fd" else result.method or args.engine,
            "engine": args.engine,
            "level": "flat" if level is None else level,
            "expanded": result.expanded,
            "reason": result.reason,
            "domain": domain.name,
            "problem": problem.name,
        }
        print(json.dumps(doc, indent=2))
    elif result.solved:
        for a in actions:
            print(a)
    else:
        print(f"{result.status.value}: {result.reason}" if result.reason else result.status.value)
    if not args.json:
        what = SEARCHES.get(result.method, result.method) if args.engine != "fd" else "Fast Downward"
        cost = f", cost {result.plan.cost(problem.init):g}" if result.plan is not None else ""
        print(f"nowplan plan: {result.status.value} by {result.method or args.engine} ({what}){cost}, "
              f"{result.expanded} expanded, {elapsed:.3f} s", file=sys.stderr)
    return 0 if result.solved else 1
