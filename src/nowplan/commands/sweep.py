"""``nowplan sweep``: run every strategy × seed of a scenario into a resumable store."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from nowplan.commands.common import positive_float, positive_int
from nowplan.errors import ScenarioError


def register(sub: Any) -> None:
    p = sub.add_parser(
        "sweep",
        help="run strategies × seeds of a scenario into a resumable SQLite store",
        description=(
            "Run every combination of --scenario, --strategies and --seeds once and store one record "
            "per configuration in --store. Runs already in the store are skipped, so an interrupted "
            "sweep (even one killed with SIGKILL) resumes by running the same command again."
        ),
    )
    p.add_argument("--domain", required=True, help="a registered domain, e.g. logistics")
    p.add_argument("--scenario", required=True, help=(
        "a scenario of the domain, or several joined by ','; a fault level rides on the name: "
        "'small?failure=0.5&exogenous=0.25' (knobs: failure, exogenous, sigma_per_m, miss)"))
    p.add_argument("--strategies", required=True, help="strategies joined by ',', e.g. hpn,flat,hpn+aggressive")
    p.add_argument("--seeds", required=True, help="'0-9', '0,3,5', '7' or a mix such as '0-4,10'")
    p.add_argument("--store", required=True, type=Path, help="SQLite file for the run records")
    p.add_argument("--backend", choices=("local", "ray"), default="local",
                   help="local worker processes (default) or Ray (pip install 'nowplan[ray]')")
    p.add_argument("--jobs", type=positive_int, help="runs at a time (default: CPU count)")
    p.add_argument("--time-limit", type=positive_float, default=600.0,
                   help="seconds per run (default 600); a run that overruns it is stopped and recorded")
    p.add_argument("--address", help="Ray cluster to join ('auto' or HOST:PORT); needs --backend ray")
    p.add_argument("--retry-errors", action="store_true", help="run again the configurations that crashed")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress bar (there is none either when standard error is not a terminal)")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from nowplan.experiments.progress import starting, wanted

    show = not args.no_progress and wanted(sys.stderr)
    loading = starting(f"sweep {args.domain}", enabled=show)  # loading the domain takes a second or two
    try:
        from nowplan.experiments.store import Store
        from nowplan.experiments.sweep import (
            SweepSpec,
            SweepState,
            make_backend,
            parse_names,
            parse_seeds,
            run_sweep,
        )

        spec = SweepSpec(
            domain=args.domain,
            scenarios=tuple(parse_names(args.scenario, "scenarios")),
            strategies=tuple(parse_names(args.strategies, "strategies")),
            seeds=tuple(parse_seeds(args.seeds)),
            time_limit=args.time_limit,
        )
        spec.validate()  # before touching the store: bad names are one-line errors
    finally:
        loading.close()
    if args.address and args.backend != "ray":
        raise ScenarioError("--address is for the Ray backend; add --backend ray")
    backend = make_backend(args.backend, args.jobs, args.address)
    spec.check_runs()  # a strategy or fault level a run would refuse: one line, exit 2, no store
    with Store(args.store) as store:
        result = run_sweep(
            spec, store, backend, retry_errors=args.retry_errors,
            progress=show, progress_file=sys.stderr, check=False,
        )
    print(result.summary())
    if result.state is not SweepState.COMPLETE:
        return 130
    from nowplan.experiments.records import RunStatus

    crashed = sum(1 for r in result.records if r.status is not RunStatus.DONE)
    return 1 if crashed else 0  # a crashed or killed run is a failure of the sweep, not of a strategy
