"""Where RCHPN leaves cost on the table on small marsupial problems (issue 17, seed 002).

For each problem (regime, size, trial) it runs HPN and RCHPN (``marsupial_trips.breakdown``: Travel,
Load/Unload, loader work, batches per vehicle) and prices a *reference plan*: every leg of the
packages' routes (truck to the airport, plane, truck to the destination; one leg if origin and
destination share a city) is driven by its vehicle in the fewest trips into which the leg's
packages can be split so that each trip's packages fit the empty bay by the domain's own greedy
packer (``grid.greedy_pack``, two storage cells left for the loader; found by enumerating the
partitions, so only for small problems), each trip the vehicle's shortest route from where it
stands (or was) to the pick-up place and on to the drop place.  Loads and Unloads are those of
every plan (20 per package and leg); loader work is charged at HPN's rate per Load/Unload (one
package in an otherwise empty bay), which a shared bay cannot beat.  The reference is the cost of
an executable schedule where a vehicle may wait for the one before it (waiting is free) up to the
packer's geometry, so it is a good plan, not an optimum or a bound; with the trips capped at
``max_combined`` packages (RCHPN's complexity limit: a combined step of at most 4 Loads) it
shows what the limit costs.

    .venv/bin/python benchmarks/marsupial_rcost12.py --regime single --sizes 3-6 --trials 0-3
"""

from __future__ import annotations

import argparse
import json
from collections import deque
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import Any

from marsupial_trips import breakdown

from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.grid import greedy_pack
from nowplan.domains.marsupial.problems import generate
from nowplan.domains.marsupial.scenarios import episode
from nowplan.experiments.sweep import parse_seeds


def partitions(items: Sequence[str]) -> Iterator[list[list[str]]]:
    """Every set partition of ``items`` (Bell(n); n <= 8 here)."""
    if not items:
        yield []
        return
    first, rest = items[0], items[1:]
    for part in partitions(rest):
        for i in range(len(part)):
            yield part[:i] + [[first, *part[i]]] + part[i + 1:]
        yield [[first], *part]


def fewest_trips(pkgs: Sequence[str], shapes: dict[str, str], bay: tuple[int, int], cap: int | None) -> int:
    rows, cols = bay
    best = len(pkgs)
    for part in partitions(list(pkgs)):
        if len(part) >= best:
            continue
        if cap is not None and any(len(g) > cap for g in part):
            continue
        if all(greedy_pack(rows, cols, (), [shapes[p] for p in g]) is not None for g in part):
            best = len(part)
    return best


def distances(graph: dict[str, set[str]], src: str) -> dict[str, int]:
    d, todo = {src: 0}, deque([src])
    while todo:
        x = todo.popleft()
        for y in graph.get(x, ()):
            if y not in d:
                d[y] = d[x] + 1
                todo.append(y)
    return d


def reference(regime: str, n: int, trial: int, cap: int | None, per_op_loader: float) -> dict[str, Any]:
    """The reference plan's cost: travel (fewest packer-feasible trips per leg), Loads/Unloads, loader."""
    problem, spec = generate(regime, n, trial)
    init = problem.init
    at = dict(init.facts("at"))
    shapes = {str(p): str(s) for p, s in init.facts("shape")}
    goal = {str(a.args[0]): str(a.args[1]) for a in problem.goal.atoms}
    graph: dict[str, dict[str, set[str]]] = {}
    for a, b, v in init.facts("connected"):
        graph.setdefault(str(v), {}).setdefault(str(a), set()).add(str(b))
    city = {loc: loc.split("-")[0] for g in graph.values() for loc in g}
    truck_of = {city[next(iter(g))]: v for v, g in graph.items() if v != spec.plane}
    legs: dict[tuple[str, str, str], list[str]] = {}
    for p, g in goal.items():
        o = str(at[p])
        if o == g:
            continue
        ap_o, ap_g = f"{city[o]}-ap", f"{city[g]}-ap"
        route = ([(truck_of[city[o]], o, g)] if city[o] == city[g] else
                 [(truck_of[city[o]], o, ap_o), (spec.plane, ap_o, ap_g), (truck_of[city[g]], ap_g, g)])
        for v, a, b in route:
            if a != b:
                legs.setdefault((v, a, b), []).append(p)
    travel, trips, ops = 0, {}, 0
    for (v, a, b), pkgs in sorted(legs.items()):
        if sum(1 for (w, _, _) in legs if w == v) > 1:
            raise SystemExit(f"marsupial_rcost12: {regime}-{n} t{trial}: vehicle {v} has several legs; "
                             "the reference handles one leg per vehicle (use --regime single)")
        k = fewest_trips(pkgs, shapes, spec.bays[v], cap)
        da, db = distances(graph[v], str(at[v])), distances(graph[v], a)
        travel += 10 * (da[a] + db[b] + (k - 1) * 2 * db[b])
        trips[v] = k
        ops += 2 * len(pkgs)
    return {"travel": travel, "load_unload": 10 * ops, "loader": per_op_loader * ops,
            "cost": travel + 10 * ops + per_op_loader * ops, "trips": trips}


def loader_ops(regime: str, n: int, trial: int, strategy: str) -> dict[str, int]:
    """The loader's operators by kind, and the Loads + Unloads, in one run (grasps beyond one per
    Load/Unload are packages moved aside)."""
    ep = episode(regime, n, trial)
    timed_run(ep, strategy, trial, 600.0)
    out = {"load_unload": 0, "loader_move": 0, "loader_grasp": 0, "loader_place": 0}
    for a in ep.world.asked:
        key = "load_unload" if a.name in ("load", "unload") else a.name
        if key in out:
            out[key] += 1
    return out


def fd_table(rows: list[dict[str, Any]], fd_path: Path) -> None:
    """Fast Downward's flat plans (``marsupial_rcost12_flat.py`` rows) beside HPN, RCHPN and the reference."""
    fd = {(r["problem"], r["trial"]): r for r in (json.loads(x) for x in fd_path.read_text().splitlines() if x.strip())}
    print("| problem | HPN | RCHPN | reference | FD first plan | FD best plan (plans, CPU s) |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        f = fd.get((r["problem"], r["trial"]))
        if f is None:
            continue
        first = "-" if f["first_cost"] is None else f"{f['first_cost']:g}"
        best = "-" if f["best_cost"] is None else f"{f['best_cost']:g}"
        print(f"| {r['problem']} t{r['trial']} | {r['hpn']:g} | {r['rchpn']:g} | {r['ref']['cost']:.0f} | {first} "
              f"| {best} ({f['plans']}, {f['cpu_s']:g}) |")
    print()


def summarize(path: Path, fd_path: Path | None = None) -> None:
    """Means over the stored rows: decreases against HPN and where RCHPN's extra cost over the reference lies."""
    rows = [json.loads(x) for x in path.read_text().splitlines() if x.strip()]
    if fd_path is not None:
        fd_table(rows, fd_path)

    def dec(r: dict[str, Any], cost: float) -> float:
        return 100.0 * (float(r["hpn"]) - cost) / float(r["hpn"])

    def mean(xs: list[float]) -> float:
        return sum(xs) / len(xs)

    print("| packages | problems | RCHPN decrease % | reference % | reference capped % | "
          "RCHPN with the reference's travel % |")
    print("|---|---|---|---|---|---|")
    for n in sorted({int(r["problem"].split("-")[1]) for r in rows}) + [0]:
        rs = [r for r in rows if n == 0 or r["problem"].endswith(f"-{n}")]
        print(f"| {n or 'all'} | {len(rs)} | {mean([dec(r, r['rchpn']) for r in rs]):.1f} | "
              f"{mean([dec(r, r['ref']['cost']) for r in rs]):.1f} | "
              f"{mean([dec(r, r['capped']['cost']) for r in rs]):.1f} | "
              f"{mean([dec(r, r['rchpn'] - r['rchpn_travel'] + r['ref']['travel']) for r in rs]):.1f} |")
    travel = sum(r["rchpn_travel"] - r["ref"]["travel"] for r in rows)
    capped = sum(r["rchpn_travel"] - r["capped"]["travel"] for r in rows)
    loader = sum(r["rchpn_loader"] - r["ref"]["loader"] for r in rows)
    ops = {s: {k: sum(r["loader_ops"][s][k] for r in rows) for k in rows[0]["loader_ops"][s]}
           for s in ("hpn", "hpn+peephole")}
    print(f"\nRCHPN over the reference, summed over {len(rows)} problems: "
          f"{sum(r['rchpn'] - r['ref']['cost'] for r in rows):.0f} of RCHPN's {sum(r['rchpn'] for r in rows):.0f} "
          f"(HPN {sum(r['hpn'] for r in rows):.0f}): travel {travel:.0f} "
          f"({travel - capped:.0f} of it the cap of --cap packages per trip, {capped:.0f} over the capped reference), loader {loader:.0f}")
    print(f"problems where RCHPN's travel is the reference's: "
          f"{sum(1 for r in rows if r['rchpn_travel'] == r['ref']['travel'])}; the capped reference's: "
          f"{sum(1 for r in rows if r['rchpn_travel'] == r['capped']['travel'])}")
    for s, o in ops.items():
        print(f"{s}: {o['load_unload']} Loads/Unloads, loader moves {o['loader_move']}, "
              f"grasps {o['loader_grasp']}, places {o['loader_place']}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--regime", default="single")
    ap.add_argument("--sizes", default="3-6")
    ap.add_argument("--trials", default="0-3")
    ap.add_argument("--cap", type=int, default=4, help="packages per trip in the capped reference")
    ap.add_argument("--out", type=Path, help="JSON lines, one per problem")
    ap.add_argument("--summarize", type=Path, help="print the means of stored rows and stop")
    ap.add_argument("--fd", type=Path, help="with --summarize: marsupial_rcost12_flat.py rows to show beside them")
    args = ap.parse_args()
    if args.summarize:
        summarize(args.summarize, args.fd)
        return
    print("| problem | HPN | RCHPN (travel / loader) | reference (travel / loader) [trips] | capped at "
          f"{args.cap} (travel) | RCHPN decrease % | reference decrease % | RCHPN trips [packages] |")
    print("|---|---|---|---|---|---|---|---|")
    for n in parse_seeds(args.sizes):
        for t in parse_seeds(args.trials):
            h = breakdown(args.regime, n, t, "hpn")
            r = breakdown(args.regime, n, t, "hpn+peephole")
            walks = {s: loader_ops(args.regime, n, t, s) for s in ("hpn", "hpn+peephole")}
            rate = (h["loader_load"] + h["loader_unload"]) / (h["load_unload"] / 10)
            ref = reference(args.regime, n, t, None, rate)
            capped = reference(args.regime, n, t, args.cap, rate)
            row = {"problem": f"{args.regime}-{n}", "trial": t, "hpn": h["cost"], "rchpn": r["cost"],
                   "rchpn_travel": r["travel"], "rchpn_loader": r["loader_load"] + r["loader_unload"],
                   "hpn_loader": h["loader_load"] + h["loader_unload"], "ref": ref, "capped": capped,
                   "rchpn_trips": {v: b for v, (b, _, _) in r["trips"].items()},
                   "rchpn_batches": {v: g for v, (_, _, g) in r["trips"].items()},
                   "loader_ops": walks}
            if args.out:
                with args.out.open("a") as f:
                    f.write(json.dumps(row) + "\n")
            dec = 100 * (h["cost"] - r["cost"]) / h["cost"]
            rdec = 100 * (h["cost"] - ref["cost"]) / h["cost"]
            batches = "; ".join(f"{v} {b} {g}" for v, (b, _, g) in r["trips"].items())
            print(f"| {args.regime}-{n} t{t} | {h['cost']:g} | {r['cost']:g} ({r['travel']:g} / "
                  f"{row['rchpn_loader']:g}) | {ref['cost']:.0f} ({ref['travel']} / {ref['loader']:.0f}) "
                  f"{ref['trips']} | {capped['cost']:.0f} ({capped['travel']}) | {dec:.1f} | {rdec:.1f} "
                  f"| {batches} |", flush=True)


if __name__ == "__main__":
    main()
