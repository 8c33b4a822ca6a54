"""A flat STRIPS version of a marsupial problem, for classical planners (seed 002 V-B).

Every grid cell of every bay is an object; packages are *placed* at an
anchor cell and cover the cells of their shape; the loader walks one cell
per ``move``.  Operators: ``load-<shape>``, ``unload-<shape>``,
``travel-<rows>x<cols>`` (the load region free, the loader in storage and
empty), ``move``, ``grasp-<shape>`` and ``place-<shape>``.  The result is an
ordinary core :class:`~nowplan.core.domain.Problem` with boolean atoms and
constant costs, so :func:`nowplan.io.pddl_write.write_pddl` writes it and
Fast Downward or pyperplan can solve it.

Differences from the hierarchical model: Load and Unload only need the
package's own cells at the anchor free, not the whole load region (in the
flat planner's favour); a walk of the loader is several ``move`` steps
(longer plans for the flat planner) — :func:`rescore` charges a run of
consecutive moves once, as our ``loader_move`` does, so costs compare.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from typing import Any

from nowplan.core.atoms import Atom, Goal, Var, atom
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import Operator, Precondition
from nowplan.core.state import State
from nowplan.domains.marsupial.grid import SHAPES, STEPS, Hold, cells, in_storage, inside, load_anchor
from nowplan.errors import ModelError

# packages and vehicles are both "at" a location; every predicate argument is typed (some PDDL
# readers reject the implicit ``object`` type in predicate declarations)
TYPES: dict[str, str | None] = {"thing": None, "package": "thing", "vehicle": "thing", "location": None,
                                "cell": None}


def _cell(v: str, rc: tuple[int, int]) -> str:
    return f"{v}-r{rc[0]}c{rc[1]}"


def _pre(*atoms: Atom) -> tuple[Precondition, ...]:
    return tuple(Precondition(a, 0) for a in atoms)


def _operators(bays: Iterable[tuple[int, int]]) -> tuple[Operator, ...]:
    p, v, l, a, b, lc, c1, c2 = (Var(n) for n in ("p", "v", "l", "a", "b", "lc", "c1", "c2"))
    ops: list[Operator] = [
        Operator("move", (v, c1, c2),
                 _pre(atom("loader", v, c1), atom("adj", c1, c2), atom("free", c2)),
                 (atom("loader", v, c2), atom("loader", v, c1, value=False)),
                 cost=1.0, param_types=("vehicle", "cell", "cell")),
    ]
    for shape, rel in SHAPES.items():
        cs = tuple(Var(f"c{i}") for i in range(len(rel)))
        ct = ("cell",) * len(cs)
        shape_cells = atom(f"cells-{shape}", a, *cs)
        frees = [atom("free", c) for c in cs]
        ops.append(Operator(
            f"load-{shape}", (p, v, l, a, lc, *cs),
            _pre(atom("reachable", l, v), atom("at", p, l), atom("at", v, l), atom(f"is-{shape}", p),
                 atom("load-anchor", a, v), shape_cells, *frees, atom("loader", v, lc), atom("storage", lc),
                 atom("empty", v)),
            (atom("in", p, v), atom("at", p, l, value=False), atom("placed", p, a),
             *(atom("free", c, value=False) for c in cs)),
            cost=10.0, param_types=("package", "vehicle", "location", "cell", "cell", *ct)))
        ops.append(Operator(
            f"unload-{shape}", (p, v, l, a, lc, *cs),
            _pre(atom("reachable", l, v), atom("in", p, v), atom("at", v, l), atom("placed", p, a),
                 atom("load-anchor", a, v), atom(f"is-{shape}", p), shape_cells, atom("loader", v, lc),
                 atom("storage", lc), atom("empty", v)),
            (atom("at", p, l), atom("in", p, v, value=False), atom("placed", p, a, value=False),
             *(atom("free", c) for c in cs)),
            cost=10.0, param_types=("package", "vehicle", "location", "cell", "cell", *ct)))
        ops.append(Operator(
            f"grasp-{shape}", (v, p, a, lc, *cs),
            _pre(atom("loader", v, lc), atom("empty", v), atom("placed", p, a), atom(f"is-{shape}", p),
                 shape_cells, atom(f"near-{shape}", a, lc)),
            (atom("holding", v, p), atom("empty", v, value=False), atom("placed", p, a, value=False),
             *(atom("free", c) for c in cs)),
            cost=1.0, param_types=("vehicle", "package", "cell", "cell", *ct)))
        ops.append(Operator(
            f"place-{shape}", (v, p, a, lc, *cs),
            _pre(atom("loader", v, lc), atom("holding", v, p), atom(f"is-{shape}", p), shape_cells,
                 atom(f"near-{shape}", a, lc), *frees),
            (atom("placed", p, a), atom("empty", v), atom("holding", v, p, value=False),
             *(atom("free", c, value=False) for c in cs)),
            cost=1.0, param_types=("vehicle", "package", "cell", "cell", *ct)))
    for rows, cols in sorted(set(bays)):
        rs = tuple(Var(f"r{i}") for i in range(2 * rows))
        ops.append(Operator(
            f"travel-{rows}x{cols}", (v, a, b, lc, *rs),
            _pre(atom("connected", a, b, v), atom("at", v, a), atom(f"region-{rows}x{cols}", v, *rs),
                 *(atom("free", r) for r in rs), atom("loader", v, lc), atom("storage", lc), atom("empty", v)),
            (atom("at", v, b), atom("at", v, a, value=False)),
            cost=10.0, param_types=("vehicle", "location", "location", "cell", *("cell",) * len(rs))))
    return tuple(ops)


def _predicates(bays: Iterable[tuple[int, int]]) -> dict[str, Predicate]:
    sig = {
        "at": ("thing", "location"), "in": ("package", "vehicle"), "reachable": ("location", "vehicle"),
        "connected": ("location", "location", "vehicle"), "placed": ("package", "cell"), "free": ("cell",),
        "loader": ("vehicle", "cell"), "empty": ("vehicle",), "holding": ("vehicle", "package"),
        "adj": ("cell", "cell"), "storage": ("cell",), "load-anchor": ("cell", "vehicle"),
    }
    for shape, rel in SHAPES.items():
        sig[f"cells-{shape}"] = ("cell",) * (1 + len(rel))
        sig[f"near-{shape}"] = ("cell", "cell")
        sig[f"is-{shape}"] = ("package",)
    for rows, cols in sorted(set(bays)):
        sig[f"region-{rows}x{cols}"] = ("vehicle", *("cell",) * (2 * rows))
    return {n: Predicate(n, len(t), t) for n, t in sig.items()}


def _bay_facts(v: str, hold: Hold) -> list[Atom]:
    rows, cols = hold.rows, hold.cols
    if hold.items or hold.held is not None:
        raise ModelError(f"the flat export needs empty bays; {v} is not")
    grid = [(r, c) for r in range(rows) for c in range(cols)]
    facts = [atom("free", _cell(v, x)) for x in grid]
    facts += [atom("storage", _cell(v, x)) for x in grid if in_storage(x, rows, cols)]
    facts += [atom("adj", _cell(v, x), _cell(v, (x[0] + dr, x[1] + dc)))
              for x in grid for dr, dc in STEPS if inside((x[0] + dr, x[1] + dc), rows, cols)]
    facts += [atom("load-anchor", _cell(v, load_anchor(cols)), v), atom("loader", v, _cell(v, hold.loader)),
              atom("empty", v)]
    region = [_cell(v, (r, c)) for c in (cols - 2, cols - 1) for r in range(rows)]
    facts.append(atom(f"region-{rows}x{cols}", v, *region))
    for shape in SHAPES:
        for anchor in grid:
            cs = cells(shape, anchor)
            if not all(inside(x, rows, cols) for x in cs):
                continue
            facts.append(atom(f"cells-{shape}", _cell(v, anchor), *(_cell(v, x) for x in cs)))
            near = {(x[0] + dr, x[1] + dc) for x in cs for dr, dc in STEPS} - set(cs)
            facts += [atom(f"near-{shape}", _cell(v, anchor), _cell(v, y)) for y in near if inside(y, rows, cols)]
    return facts


def flatten(problem: Problem) -> Problem:
    """The flat STRIPS problem equivalent to a marsupial problem whose bays are empty."""
    init = problem.init
    vehicles = [o for o, t in problem.objects.items() if t in ("truck", "plane")]
    holds = {v: init.value(("cargo", (v,))) for v in vehicles}
    bays = [(h.rows, h.cols) for h in holds.values()]
    domain = Domain("marsupial-flat", _predicates(bays), _operators(bays), TYPES)
    objects: dict[str, str | None] = {}
    facts: list[Atom] = []
    for o, t in problem.objects.items():
        objects[o] = {"truck": "vehicle", "plane": "vehicle"}.get(str(t), t)
    for v, h in holds.items():
        for r in range(h.rows):
            for c in range(h.cols):
                objects[_cell(v, (r, c))] = "cell"
        facts += _bay_facts(v, h)
    for pred in ("at", "in", "reachable", "connected"):
        facts += [Atom(pred, tuple(args)) for args in init.facts(pred)]
    facts += [atom(f"is-{shape}", pkg) for pkg, shape in init.facts("shape")]
    return Problem(domain, objects, State(facts), Goal(problem.goal.atoms), problem.name + "-flat")


def rescore(actions: Sequence[str]) -> float:
    """Cost of a flat plan with our cost model: a run of one vehicle's moves is one loader_move."""
    total, last_move = 0.0, None
    for a in actions:
        name, *args = a.strip("()").split()
        if name == "move":
            if last_move != args[0]:
                total += 1.0
            last_move = args[0]
            continue
        last_move = None
        total += 10.0 if name.split("-")[0] in ("load", "unload", "travel") else 1.0
    return total


def summary(problem: Problem) -> dict[str, Any]:
    flat = flatten(problem)
    return {"objects": len(flat.objects), "facts": len(flat.init), "operators": len(flat.domain.operators)}
