"""Seeded problem generators for the 13 classical domains, and the checked-in instance set.

``GENERATORS[domain](**params, seed=N)`` returns PDDL problem text; the same
arguments always give the same text.  ``INSTANCES`` lists the parameters and
seeds of the checked-in problems ``<domain>/p01.pddl ...`` (sizes of the
first IPC instances of each domain).  Usage:

    python benchmarks/classical/generate.py                # rewrite every checked-in instance
    python benchmarks/classical/generate.py --domains gripper,rovers
    python benchmarks/classical/generate.py --scale /tmp/scale    # the scale-up set (SCALE), not checked in
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


# (parameters, seed) of the scale-up set s01, s02, ... per domain: sizes like the IPC mid-range problems
# (issue 19 / the held-out competition files), written outside the checked-in set (`--scale DIR`); seeds
# 101, 102, ... so that no scale instance repeats a checked-in one
SCALE: dict[str, list[tuple[Params, int]]] = {
    "blocksworld": [({"blocks": n}, 100 + k) for k, n in enumerate((10, 12, 14, 15, 17), start=1)],
    "logistics": [({"cities": c, "places": p, "airplanes": a, "packages": n}, 100 + k)
                  for k, (c, p, a, n) in enumerate(((4, 3, 2, 12), (5, 3, 2, 16), (5, 4, 3, 20), (6, 3, 3, 25),
                                                     (6, 4, 3, 30)), start=1)],
    "depots": [({"depots": d, "distributors": s, "trucks": t, "crates": n}, 100 + k)
               for k, (d, s, t, n) in enumerate(((1, 2, 2, 8), (2, 2, 2, 10), (2, 3, 2, 12), (2, 3, 3, 15),
                                                  (3, 3, 3, 18)), start=1)],
    "driverlog": [({"drivers": d, "trucks": t, "packages": p, "locations": n}, 100 + k)
                  for k, (d, t, p, n) in enumerate(((3, 3, 6, 8), (3, 3, 7, 10), (3, 4, 8, 12), (4, 4, 9, 14),
                                                     (4, 4, 10, 15)), start=1)],
    "gripper": [({"balls": n}, 0) for n in (16, 22, 30, 36, 42)],
    "rovers": [({"rovers": r, "waypoints": w, "objectives": o, "soil": a, "rock": b, "images": i}, 100 + k)
               for k, (r, w, o, a, b, i) in enumerate(((3, 10, 4, 4, 3, 3), (3, 12, 4, 5, 4, 4),
                                                        (4, 14, 5, 6, 5, 4), (4, 16, 5, 7, 6, 5),
                                                        (5, 18, 6, 8, 7, 6)), start=1)],
    "satellite": [({"satellites": s, "instruments": i, "modes": m, "stars": st, "targets": t, "images": g}, 100 + k)
                  for k, (s, i, m, st, t, g) in enumerate(((3, 2, 3, 4, 8, 8), (4, 3, 3, 5, 10, 10),
                                                           (4, 3, 4, 5, 12, 12), (5, 3, 4, 6, 15, 14),
                                                           (6, 3, 5, 6, 18, 16)), start=1)],
    "zenotravel": [({"aircraft": a, "persons": p, "cities": c}, 100 + k)
                   for k, (a, p, c) in enumerate(((3, 7, 6), (3, 8, 7), (4, 10, 8), (5, 12, 9), (5, 15, 10)),
                                                 start=1)],
    "miconic": [({"passengers": n, "floors": 2 * n}, 100 + n) for n in (10, 14, 18, 22, 26)],
    "barman": [({"shots": g + 1, "cocktails": c, "goals": g}, 100 + k)
               for k, (c, g) in enumerate(((4, 5), (4, 6), (5, 7), (5, 8), (6, 10)), start=1)],
    "nomystery": [({"locations": n, "packages": p}, 100 + k)
                  for k, (n, p) in enumerate(((8, 7), (9, 8), (10, 9), (11, 10), (12, 12)), start=1)],
    "visitall": [({"width": n, "height": n}, 100 + n) for n in (8, 10, 12, 14, 16)],
    "floortile": [({"rows": r, "columns": c, "robots": k}, 100 + i)
                  for i, (r, c, k) in enumerate(((4, 4, 2), (5, 3, 2), (5, 4, 2), (5, 4, 3), (6, 4, 3)), start=1)],
}

def generate(domain: str, params: Params, seed: int) -> str:
    """Problem text of ``domain`` with ``params`` and ``seed``."""
    if domain not in GENERATORS:
        raise ValueError(f"unknown domain '{domain}'; known: {', '.join(DOMAINS)}")
    return GENERATORS[domain](**params, seed=seed)


def domain_file(domain: str, root: Path = HERE) -> Path:
    return root / domain / "domain.pddl"


def instance_files(domain: str, root: Path = HERE, prefix: str = "p") -> list[Path]:
    """The problems ``<root>/<domain>/<prefix>NN.pddl`` (the checked-in ones by default), in order."""
    return sorted((root / domain).glob(f"{prefix}[0-9][0-9].pddl"))


def write_instances(domains: Sequence[str] = DOMAINS, root: Path = HERE, *, scale: bool = False) -> list[Path]:
    """Write ``<root>/<domain>/pNN.pddl`` (``sNN.pddl`` of :data:`SCALE` with ``scale``); returns the paths."""
    table, prefix = (SCALE, "s") if scale else (INSTANCES, "p")
    out = []
    for d in domains:
        for k, (params, seed) in enumerate(table[d], start=1):
            path = root / d / f"{prefix}{k:02d}.pddl"
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
    ap.add_argument("--scale", type=Path, metavar="DIR",
                    help="write the scale-up set (SCALE: sNN.pddl, IPC mid-range sizes) under DIR instead")
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
    if args.scale is not None:
        for p in write_instances(domains, args.scale, scale=True):
            print(p)
        return 0
    for p in write_instances(domains):
        print(p.relative_to(HERE))
    return 0


if __name__ == "__main__":
    sys.exit(main())
