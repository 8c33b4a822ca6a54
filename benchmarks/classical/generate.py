"""Seeded problem generators for the 13 classical domains, and the checked-in instance set.

``GENERATORS[domain](**params, seed=N)`` returns PDDL problem text; the same
arguments always give the same text.  ``INSTANCES`` lists the parameters and
seeds of the checked-in problems ``<domain>/p01.pddl ...`` (sizes of the
first IPC instances of each domain).  Usage:

    python benchmarks/classical/generate.py                # rewrite every checked-in instance
    python benchmarks/classical/generate.py --domains gripper,rovers
    python benchmarks/classical/generate.py --domain logistics --seed 7 cities=3 packages=6   # to stdout
"""

from __future__ import annotations

import sys
from collections.abc import Callable, Sequence
from pathlib import Path

if __name__ == "__main__":  # run as a script: make ``benchmarks.classical`` importable
    sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from benchmarks.classical import gen_misc, gen_transport

HERE = Path(__file__).resolve().parent

GENERATORS: dict[str, Callable[..., str]] = {
    "blocksworld": gen_misc.blocksworld,
    "logistics": gen_transport.logistics,
    "depots": gen_transport.depots,
    "driverlog": gen_transport.driverlog,
    "gripper": gen_transport.gripper,
    "rovers": gen_misc.rovers,
    "satellite": gen_misc.satellite,
    "zenotravel": gen_transport.zenotravel,
    "miconic": gen_transport.miconic,
    "barman": gen_misc.barman,
    "nomystery": gen_transport.nomystery,
    "visitall": gen_misc.visitall,
    "floortile": gen_misc.floortile,
}
DOMAINS = tuple(GENERATORS)

Params = dict[str, int]

# (parameters, seed) of p01, p02, ... per domain, in increasing size
INSTANCES: dict[str, list[tuple[Params, int]]] = {
    "blocksworld": [({"blocks": n}, s) for n, s in ((4, 1), (5, 2), (6, 3), (7, 4), (9, 5))],
    "logistics": [
        ({"cities": 2, "places": 2, "airplanes": 1, "packages": 4}, 1),
        ({"cities": 2, "places": 2, "airplanes": 1, "packages": 5}, 2),
        ({"cities": 2, "places": 3, "airplanes": 1, "packages": 6}, 3),
        ({"cities": 3, "places": 2, "airplanes": 1, "packages": 6}, 4),
        ({"cities": 3, "places": 3, "airplanes": 2, "packages": 8}, 5),
    ],
    "depots": [({"depots": 1, "distributors": 2, "trucks": 2, "crates": n}, s)
               for n, s in ((2, 1), (3, 2), (4, 3), (5, 4), (6, 5))],
    "driverlog": [
        ({"drivers": 2, "trucks": 2, "packages": 2, "locations": 3}, 1),
        ({"drivers": 2, "trucks": 2, "packages": 3, "locations": 3}, 2),
        ({"drivers": 2, "trucks": 2, "packages": 4, "locations": 4}, 3),
        ({"drivers": 3, "trucks": 2, "packages": 4, "locations": 5}, 4),
        ({"drivers": 2, "trucks": 3, "packages": 5, "locations": 6}, 5),
    ],
    "gripper": [({"balls": n}, 0) for n in (4, 6, 8, 10, 12)],
    "rovers": [
        ({"rovers": 1, "waypoints": 4, "objectives": 2, "soil": 1, "rock": 1, "images": 1}, 1),
        ({"rovers": 1, "waypoints": 5, "objectives": 2, "soil": 2, "rock": 1, "images": 1}, 2),
        ({"rovers": 2, "waypoints": 6, "objectives": 2, "soil": 2, "rock": 2, "images": 1}, 3),
        ({"rovers": 2, "waypoints": 7, "objectives": 3, "soil": 2, "rock": 2, "images": 2}, 4),
        ({"rovers": 2, "waypoints": 8, "objectives": 3, "soil": 3, "rock": 2, "images": 2}, 5),
    ],
    "satellite": [
        ({"satellites": 1, "instruments": 1, "modes": 3, "stars": 2, "targets": 3, "images": 2}, 1),
        ({"satellites": 1, "instruments": 2, "modes": 3, "stars": 2, "targets": 4, "images": 3}, 2),
        ({"satellites": 2, "instruments": 2, "modes": 3, "stars": 3, "targets": 4, "images": 4}, 3),
        ({"satellites": 2, "instruments": 2, "modes": 3, "stars": 3, "targets": 5, "images": 5}, 4),
        ({"satellites": 3, "instruments": 2, "modes": 3, "stars": 3, "targets": 6, "images": 6}, 5),
    ],
    "zenotravel": [
        ({"aircraft": 1, "persons": 2, "cities": 3}, 1),
        ({"aircraft": 1, "persons": 3, "cities": 3}, 2),
        ({"aircraft": 2, "persons": 4, "cities": 4}, 3),
        ({"aircraft": 2, "persons": 5, "cities": 4}, 4),
        ({"aircraft": 2, "persons": 6, "cities": 5}, 5),
    ],
    "miconic": [({"passengers": n, "floors": 2 * n}, n) for n in (2, 3, 4, 5, 6)],
    "barman": [({"shots": g + 1, "cocktails": 3, "goals": g}, s) for g, s in ((2, 1), (3, 2), (3, 3), (4, 4), (4, 5))],
    "nomystery": [({"locations": n, "packages": k}, s) for n, k, s in ((4, 3, 1), (5, 4, 2), (6, 5, 3), (6, 6, 4),
                                                                         (7, 6, 5))],
    "visitall": [({"width": w, "height": h}, s) for w, h, s in ((3, 3, 1), (4, 4, 2), (5, 5, 3), (6, 6, 4),
                                                                 (7, 7, 5))],
    "floortile": [({"rows": r, "columns": c, "robots": k}, s) for r, c, k, s in ((2, 2, 1, 1), (3, 2, 2, 2),
                                                                                (3, 3, 2, 3), (3, 4, 2, 4),
                                                                                (4, 3, 2, 6))],
}


def generate(domain: str, params: Params, seed: int) -> str:
    """Problem text of ``domain`` with ``params`` and ``seed``."""
    if domain not in GENERATORS:
        raise ValueError(f"unknown domain '{domain}'; known: {', '.join(DOMAINS)}")
    return GENERATORS[domain](**params, seed=seed)


def domain_file(domain: str, root: Path = HERE) -> Path:
    return root / domain / "domain.pddl"


def instance_files(domain: str, root: Path = HERE) -> list[Path]:
    """The checked-in problems of ``domain``, in order."""
    return sorted((root / domain).glob("p[0-9][0-9].pddl"))


def write_instances(domains: Sequence[str] = DOMAINS, root: Path = HERE) -> list[Path]:
    """Write ``<root>/<domain>/pNN.pddl`` for the listed domains; returns the paths."""
    out = []
    for d in domains:
        for k, (params, seed) in enumerate(INSTANCES[d], start=1):
            path = root / d / f"p{k:02d}.pddl"
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(generate(d, params, seed))
            out.append(path)
    return out


def _params(items: Sequence[str]) -> Params:
    out: Params = {}
    for it in items:
        key, sep, value = it.partition("=")
        if not sep or not value.lstrip("-").isdigit():
            raise SystemExit(f"generate: expected NAME=INT, got '{it}'")
        out[key] = int(value)
    return out


def main(argv: Sequence[str] | None = None) -> int:
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--domains", default=",".join(DOMAINS), help="rewrite the checked-in instances of these")
    ap.add_argument("--domain", help="print one problem of this domain instead")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("params", nargs="*", metavar="NAME=INT", help="generator parameters (with --domain)")
    args = ap.parse_args(argv)
    if args.domain:
        try:
            sys.stdout.write(generate(args.domain, _params(args.params), args.seed))
        except (ValueError, TypeError) as exc:
            raise SystemExit(f"generate: {exc}") from None
        return 0
    domains = [d for d in args.domains.split(",") if d]
    bad = [d for d in domains if d not in GENERATORS]
    if bad:
        raise SystemExit(f"generate: unknown domain(s) {', '.join(bad)}; known: {', '.join(DOMAINS)}")
    for p in write_instances(domains):
        print(p.relative_to(HERE))
    return 0


if __name__ == "__main__":
    sys.exit(main())
