"""How often the loader jams a bay that seed 002's greedy packer says fits (marsupial logistics).

Draws random package sets (3-8 packages of the six shapes, a 3x6 or 4x8 bay,
seeded), keeps those the greedy packer fits into an empty bay
(``grid.can_share``), and loads them one by one in the drawn order, each
stowed by the loader's A* (``loader.can_stow_in_turn``, the second half of
the domain's shareability test).  Prints how many of the packer's fits the
loader could not stow in that order.  Usage:

    .venv/bin/python benchmarks/marsupial_stow_jams.py [--sets 300] [--seed 1]
"""

from __future__ import annotations

import argparse
import random

from nowplan.domains.marsupial import loader as lp
from nowplan.domains.marsupial.grid import SHAPES, SIZES, Hold, can_share


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sets", type=int, default=300, help="random package sets to draw")
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    rng = random.Random(args.seed)
    names = sorted(SHAPES)
    fits = jams = 0
    for _ in range(args.sets):
        rows, cols = rng.choice(SIZES)
        pkgs = [(f"p{i}", rng.choice(names)) for i in range(rng.randint(3, 8))]
        empty = Hold.empty(rows, cols)
        if can_share(empty, None, dict(pkgs)):
            fits += 1
            if not lp.can_stow_in_turn(empty, None, pkgs):
                jams += 1
                print(f"jam: {rows}x{cols} {[s for _, s in pkgs]}")
    print(f"{args.sets} sets (seed {args.seed}): the packer fits {fits}; the loader jams {jams} of them")


if __name__ == "__main__":
    main()
