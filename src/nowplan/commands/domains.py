"""``nowplan domains``: the domains nowplan finds (built-in and plugins), with their scenarios."""

from __future__ import annotations

import argparse
import json
from typing import Any


def register(subparsers: Any) -> None:
    p = subparsers.add_parser(
        "domains",
        help="list the domains nowplan finds (built-in and plugins) and their scenarios",
        description="Lists every domain found through the 'nowplan.domains' entry points, "
                    "NOWPLAN_DOMAINS and --import, with where it came from and its scenarios.",
    )
    p.add_argument("--json", action="store_true", help="print a JSON document")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    from nowplan.domains.registry import domain_names, get_domain

    specs = [get_domain(n) for n in domain_names()]
    if args.json:
        print(json.dumps([{"name": s.name, "description": s.description, "source": s.source,
                           "scenarios": sorted(s.scenarios), "default_scenario": s.default_scenario,
                           "demo": s.demo is not None, "renderer": s.renderer is not None} for s in specs],
                         indent=2))
        return 0
    for s in specs:
        extras = ", ".join(x for x, ok in (("demo", s.demo), ("renderer", s.renderer)) if ok)
        print(f"{s.name}: {s.description}")
        print(f"  from {s.source or 'register()'}" + (f"; has {extras}" if extras else ""))
        print(f"  scenarios: {', '.join(sorted(s.scenarios))} (default {s.default_scenario or '-'})")
    return 0
