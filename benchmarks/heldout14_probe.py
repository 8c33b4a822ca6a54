"""Two probes of the held-out tidy house (examples/tidy) through the public API (helper heldout14).

1. A generator with two outputs of which a goal binds one: ``spot`` proposing ``(u, r)`` (a free
   floor spot and its room) is called for ``place(cup, rack, r)`` too, with ``u`` bound; the
   planner drops every proposal that disagrees with ``u = rack``, so ``on(cup, rack)`` is reported
   "unsolvable (search space exhausted)" with nothing naming the generator.  With the one output
   ``u`` (the example's) it is solved.
2. One planner call for the whole goal, at the top level (what ``plan`` does without ``levels``)
   and concretely (what flat plans: ``LevelMap(0)``, which ``nowplan.api`` does not export), with
   and without the generator ``spot`` whose values are objects of the problem anyway.

    PYTHONPATH=src:examples/tidy python benchmarks/heldout14_probe.py [--time-limit 10]
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Iterator, Mapping
from dataclasses import replace
from typing import Any

from nowplan.api import Domain, Generator, Goal, PlannerConfig, Var, atom, plan, reads_nothing
from nowplan.core.levels import LevelMap  # not in nowplan.api: plan() is abstract without it

from tidy_domain import model
from tidy_domain.scenarios import problem

U, R = Var("u"), Var("r")


def spots_and_rooms(bindings: Mapping[Var, Any], goal: Any, belief: Any, context: Any) -> Iterator[dict[Var, Any]]:
    """``model.free_spots`` with the spot's room as a second output."""
    rooms = {str(s): str(rm) for (s, rm) in belief.facts("in")}
    for row in model.free_spots(bindings, goal, belief, context):
        yield {U: row[U], R: rooms[str(row[U])]}


def with_generator(gen: Generator) -> Domain:
    ops = tuple(replace(op, generators=(gen,)) if op.name == "place" else op for op in model.OPERATORS)
    return Domain("tidy", model.PREDICATES, ops, types=model.TYPES, conflicts=model.CONFLICTS)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else None)
    ap.add_argument("--time-limit", type=float, default=10.0)
    a = ap.parse_args()
    prob, belief = problem(0, "tidy")
    cfg = PlannerConfig(time_limit=a.time_limit)
    two = with_generator(Generator("spot", (U, R), spots_and_rooms, (U, R), reads=reads_nothing))
    one = with_generator(Generator("spot", (U,), model.free_spots, (), reads=reads_nothing))
    goal = Goal.of([atom("on", "cup", "rack")], model.DOMAIN.rules)
    for name, dom in (("outputs (u, r)", two), ("output u", one)):
        res = plan(dom, prob.objects, belief, goal, config=cfg)
        print(f"1. on(cup, rack), generator {name}: {res.status.value} {res.reason}")
    for lv_name, levels in (("top level", None), ("concrete", LevelMap(0))):
        for name, dom in (("no generator", model.DOMAIN), ("generator spot", one)):
            t0 = time.process_time()
            res = plan(dom, prob.objects, belief, prob.goal, levels, config=cfg)
            steps = len(res.plan.steps) - 1 if res.plan is not None else None
            print(f"2. the whole goal, {lv_name}, {name}: {res.status.value} {res.reason} steps={steps} "
                  f"cpu={time.process_time() - t0:.2f} s")


if __name__ == "__main__":
    main()
