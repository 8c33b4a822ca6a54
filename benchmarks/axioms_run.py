"""``nowplan run`` on domains with derived predicates: flat planning vs the executive flat vs auto-HPN.

Builds the folder layout of ``benchmarks/ipc_check.py`` (``FOLDER/NAME/domain.pddl`` and problems) in
``--work`` from

* the repository's own domains with recursive derived predicates (``tests/data/pddl_axioms*``: doors,
  power grid, couriers, blocksworld with ``above``);
* the IPC-2004 philosophers files of ``benchmarks/ipc_fetch9.md`` (``--philosophers``, a folder with
  ``domain.pddl``, ``p01.pddl``, ``p06.pddl``; p06's goal is too large to substitute, so its derived
  predicates are evaluated by rules);
* the IPC-2004 PSR-large domain (``--psr``, a ``domain.pddl``; source in
  ``benchmarks/axioms_run_sources.md``) with problems written here, as ``benchmarks/results/axioms_check.md``
  did: ``b`` breakers, each feeding a chain of ``k`` switches with a faulty line after switch ``f``;
  every device starts closed (so the breakers are affected and must wait), and the goal feeds every
  line before the fault with no breaker affected.

and runs ``benchmarks/auto_ipc.py`` over it with the strategies ``flat`` and ``hpn`` (``nowplan run
D P --criticality auto --strategy S``), every plan and every executed run validated (Unified Planning
where its reader takes the files, else ``tests/pddl_sim.py``).

    PYTHONPATH=src .venv/bin/python benchmarks/axioms_run.py --philosophers /tmp/ipc9/philosophers \\
        --psr /tmp/axfiles/psr-large/domain.pddl --out benchmarks/results/axioms_run
"""

from __future__ import annotations

import argparse
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from benchmarks.auto_ipc import main as auto_ipc  # noqa: E402

OWN = {  # folder name -> (data directory, domain file, problem files)
    "doors": ("pddl_axioms", "doors-domain.pddl", ["doors-p01.pddl", "doors-p02.pddl"]),
    "grid": ("pddl_axioms", "grid-domain.pddl", ["grid-p01.pddl", "grid-p02.pddl"]),
    "courier": ("pddl_axioms_run", "courier-domain.pddl", ["courier-p01.pddl"]),
    "blocks-above": ("pddl_axioms_run", "blocks-above-domain.pddl", ["blocks-above-p01.pddl"]),
}
PSR = [(1, 3, 2), (2, 3, 2), (2, 4, 3), (3, 4, 2)]  # (breakers, switches per chain, fault after switch)


def psr_problem(name: str, b: int, k: int, f: int) -> str:
    """A PSR-large problem: ``b`` chains breaker - k switches, line ``l{i}-{f}`` faulty."""
    devices, lines, init, goal = [], [], [], []
    for i in range(1, b + 1):
        chain = [f"cb{i}", *(f"s{i}-{j}" for j in range(1, k + 1))]
        devices += chain
        init += [f"(breaker cb{i})", *(f"(closed {d})" for d in chain)]
        for j in range(k + 1):  # line j sits after device j of the chain (and before device j + 1)
            line = f"l{i}-{j}"
            lines.append(line)
            init.append(f"(ext {line} {chain[j]} side2)")
            if j < k:
                init += [f"(ext {line} {chain[j + 1]} side1)",
                         f"(con {chain[j]} side2 {chain[j + 1]} side1)", f"(con {chain[j + 1]} side1 {chain[j]} side2)"]
            if j < f:
                goal.append(f"(fed {line})")
        init.append(f"(faulty l{i}-{f})")
        goal.append(f"(not (affected cb{i}))")
    return (f"(define (problem {name}) (:domain psr)\n  (:objects {' '.join(devices)} - DEVICE {' '.join(lines)} - LINE)\n"
            f"  (:init {' '.join(init)})\n  (:goal (and {' '.join(goal)})))\n")


def build(work: Path, philosophers: Path | None, psr: Path | None) -> None:
    data = ROOT / "tests" / "data"
    for name, (sub, dom, probs) in OWN.items():
        d = work / name
        d.mkdir(parents=True, exist_ok=True)
        shutil.copy(data / sub / dom, d / "domain.pddl")
        for p in probs:
            shutil.copy(data / sub / p, d / p)
    if philosophers is not None:
        d = work / "philosophers"
        d.mkdir(parents=True, exist_ok=True)
        for f in ("domain.pddl", "p01.pddl", "p06.pddl"):
            shutil.copy(philosophers / f, d / f)
    if psr is not None:
        d = work / "psr-large"
        d.mkdir(parents=True, exist_ok=True)
        if psr.resolve() != (d / "domain.pddl").resolve():
            shutil.copy(psr, d / "domain.pddl")
        for n, (b, k, f) in enumerate(PSR, 1):
            (d / f"p{n:02d}.pddl").write_text(psr_problem(f"psr-b{b}-k{k}-f{f}", b, k, f))


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--philosophers", type=Path)
    ap.add_argument("--psr", type=Path)
    ap.add_argument("--work", type=Path, default=Path("/tmp/axfiles/run"))
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args(argv)
    build(args.work, args.philosophers, args.psr)
    return auto_ipc([str(args.work), "--time-limit", f"{args.time_limit:g}", "--problems", "8",
                     "--strategies", "flat,hpn", "--out", str(args.out)])


if __name__ == "__main__":
    raise SystemExit(main())
