"""Seed 000's runs with NAMO parameters overridden: the fog-pricing ablation of issue 17.

``nowplan reproduce 000`` runs the built-in scenarios with their own
parameters; this runs the same records (:func:`run_one`, the same
strategies, planner and seeds) with some :class:`Params` fields replaced in
every scenario, e.g. fog free again (``fog_pricing`` off) or a denser prior
on objects in fog, and prints the reproduction's table and target checks.

    # the full reproduction (seeds 0-9, office 0-2, 3 timings per run) with fog free
    python benchmarks/namo_fog_ablation.py --params '{"fog_pricing": false}' --out /tmp/fogfree
    # other seeds, one timing per run
    python benchmarks/namo_fog_ablation.py --seeds 10-19 --office-seeds 3-5 --repeats 1 --out /tmp/s10
    python benchmarks/namo_fog_ablation.py --params '{"fog_prior_objects": 8}' --seeds 0-9 --repeats 1 --out /tmp/p8

With ``--out DIR`` the records go to ``DIR/runs.json`` (the format
``python -m nowplan.domains.namo.combine`` reads).  Runs go one after the
other in this process (the overrides apply here only).
"""

from __future__ import annotations

import argparse
import json
from dataclasses import fields, replace
from pathlib import Path
from typing import Any

from nowplan.experiments.sweep import parse_seeds


def main(argv: list[str] | None = None) -> int:
    from nowplan.domains.namo import scenarios as S
    from nowplan.domains.namo.params import Params
    from nowplan.domains.namo.reproduction import (
        ALGORITHMS, DOMAINS, RunSpec, TIMING_REPEATS, aggregate, run_one, targets,
    )

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--params", default="{}", help='JSON object of Params fields, e.g. \'{"fog_pricing": false}\'')
    ap.add_argument("--seeds", default="0-9", help="seeds on domains 1-3 (default 0-9)")
    ap.add_argument("--office-seeds", default="0-2", help="office seeds (default 0-2; 'none' for none)")
    ap.add_argument("--repeats", type=int, default=TIMING_REPEATS, help="timings per run; the fastest counts")
    ap.add_argument("--out", type=Path, default=None, help="write DIR/runs.json")
    args = ap.parse_args(argv)
    try:
        over: dict[str, Any] = json.loads(args.params)
    except json.JSONDecodeError as e:
        ap.error(f"--params: not JSON ({e.msg}); write e.g. '{{\"fog_pricing\": false}}'")
    known = {f.name for f in fields(Params)}
    if not isinstance(over, dict) or set(over) - known:
        ap.error(f"--params: unknown field(s) {sorted(set(over) - known)}; Params has {sorted(known)}")
    base_spec = S.SCENARIOS.spec

    def spec(name: str) -> Any:
        sc = base_spec(name)
        return replace(sc, params=replace(sc.params, **over))

    S.SCENARIOS.spec = spec  # type: ignore[method-assign]  # this process only
    office: list[int] = [] if args.office_seeds == "none" else parse_seeds(args.office_seeds)
    specs = [RunSpec(label, scen, alg, s) for label, scen in DOMAINS.items() for alg in ALGORITHMS
             for s in parse_seeds(args.seeds)]
    specs += [RunSpec("office", "office", alg, s) for alg in ALGORITHMS for s in office]
    records = [run_one(s, repeats=args.repeats) for s in specs]
    rows = aggregate(records)
    cols = ("domain", "algorithm", "reached", "picks_places", "looks", "moves", "planning_ratio")
    print("| " + " | ".join(cols) + " |\n|" + "---|" * len(cols))
    for r in rows:
        print("| " + " | ".join(str(r.get(c, "")) for c in cols) + " |")
    for line in targets(rows):
        print(line)
    failed = [f"{r['domain']}/{r['algorithm']}/seed {r['seed']}: {r['outcome']} ({r['reason']})"
              for r in records if r["outcome"] != "reached"]
    print("not reached: " + ("; ".join(failed) if failed else "none"))
    if args.out is not None:
        args.out.mkdir(parents=True, exist_ok=True)
        (args.out / "runs.json").write_text(json.dumps(records, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
