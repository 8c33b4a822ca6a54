"""``nowplan criticality DOMAIN.pddl``: print the automatic criticality file of a domain.

Derives Knoblock's ordered-monotonic abstraction hierarchy from the domain
alone (:mod:`nowplan.planning.abstraction`) and prints it as a criticality
file, its levels and literal classes as comments.  The file is what
``--criticality auto`` uses; edit it and pass it back with
``--criticality FILE``.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from nowplan.commands.common import existing_file


def register(sub: Any) -> None:
    p = sub.add_parser(
        "criticality",
        help="print the automatic criticality file (abstraction hierarchy) of a PDDL domain",
        description=__doc__.split("\n\n", 1)[1] if __doc__ else None,
    )
    p.add_argument("domain", metavar="DOMAIN.pddl", type=existing_file, help="PDDL domain file")
    p.add_argument("--out", type=Path, metavar="FILE", help="write the file here instead of printing it")
    p.set_defaults(func=main)


def main(args: argparse.Namespace) -> int:
    from nowplan.io.criticality import hierarchy_text
    from nowplan.io.pddl_read import load_domain

    text = hierarchy_text(load_domain(args.domain))
    if args.out is not None:
        args.out.write_text(text, encoding="utf-8")
    else:
        print(text, end="")
    return 0
