"""Seeded NAMO episodes from scenario descriptions.

``episode(spec, seed)`` draws everything random from ``seed`` (jittered and
scattered obstacles, the world's noise), builds the true world and the
agent's initial belief (walls known, movable obstacles unknown unless the
scenario says otherwise, fog everywhere but around the robot unless
``fog`` is false) and the problem ``RobotAt(goal)``.
"""

from __future__ import annotations

import random
from collections.abc import Callable, Iterator, Mapping
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from nowplan.core.atoms import Goal, atom
from nowplan.core.domain import Domain, Problem
from nowplan.domains.namo.belief import NamoBelief, ObjectEstimate
from nowplan.domains.namo.geometry import Box, MapGeometry, Pt
from nowplan.domains.namo.maps import BUILTIN
from nowplan.domains.namo.params import Params
from nowplan.domains.namo.spec import ScenarioSpec, load_file, parse
from nowplan.domains.namo.world import NamoWorld, TrueObject
from nowplan.domains.registry import Episode
from nowplan.errors import ScenarioError


@lru_cache(maxsize=16)
def domain_for(params: Params) -> Domain:
    from nowplan.domains.namo.model import build_domain

    return build_domain(params)


def geometry_of(spec: ScenarioSpec) -> MapGeometry:
    return MapGeometry(
        width=spec.size[0], height=spec.size[1], walls=spec.walls,
        landmarks=tuple((n, Pt.of(*p)) for n, p in spec.landmarks),
        res=spec.resolution, robot_radius=spec.robot_radius,
    )


def _free_for(geom: MapGeometry, box: Box, placed: list[Box], keep: list[tuple[Pt, float]]) -> bool:
    x0, y0, x1, y1 = box.bounds
    if x0 < 0.05 or y0 < 0.05 or x1 > geom.width - 0.05 or y1 > geom.height - 0.05:
        return False
    for wx0, wy0, wx1, wy1 in geom.walls:
        if x0 < wx1 + 0.02 and wx0 - 0.02 < x1 and y0 < wy1 + 0.02 and wy0 - 0.02 < y1:
            return False
    for b in placed:
        bx0, by0, bx1, by1 = b.bounds
        if x0 < bx1 + 0.1 and bx0 - 0.1 < x1 and y0 < by1 + 0.1 and by0 - 0.1 < y1:
            return False
    return all(box.distance_to_segment(p, p) > d for p, d in keep)


def true_objects(spec: ScenarioSpec, geom: MapGeometry, rng: random.Random) -> list[TrueObject]:
    start, goal = Pt.of(*spec.start), Pt.of(*spec.goal)
    keep = [(start, spec.robot_radius + 0.3), (goal, spec.robot_radius + 0.3)]
    out: list[TrueObject] = []
    boxes: list[Box] = []
    for o in spec.objects:
        x, y = o.at
        box = Box(x, y, *o.size)
        if o.jitter > 0:
            for _ in range(50):
                cand = Box(x + rng.uniform(-o.jitter, o.jitter), y + rng.uniform(-o.jitter, o.jitter), *o.size)
                if _free_for(geom, cand, boxes, keep):
                    box = cand
                    break
        box = Box(round(box.cx, 3), round(box.cy, 3), box.w, box.h)
        boxes.append(box)
        out.append(TrueObject(o.name, box, o.appear_after))
    for s in spec.scatter:
        x0, y0, x1, y1 = s.area
        sk = [(start, spec.robot_radius + s.clearance), (goal, spec.robot_radius + s.clearance)]
        made = 0
        for _ in range(200 * max(s.count, 1)):
            if made >= s.count:
                break
            cand = Box(round(rng.uniform(x0, x1), 3), round(rng.uniform(y0, y1), 3), *s.size)
            if _free_for(geom, cand, boxes, sk):
                boxes.append(cand)
                out.append(TrueObject(f"{s.prefix}{made}", cand))
                made += 1
    return out


def initial_belief(spec: ScenarioSpec, geom: MapGeometry, objects: list[TrueObject]) -> NamoBelief:
    start = geom.grid.snap(Pt.of(*spec.start))
    observed = None if spec.fog else np.ones(geom.grid.n, dtype=bool)
    b = NamoBelief(geom, np.array([start.x, start.y]), params=spec.params, sensor=spec.sensor,
                   observed=observed)  # type: ignore[arg-type]
    truth = {o.name: o for o in objects}
    for o in spec.objects:
        if not o.known or o.name not in truth:
            continue
        t = truth[o.name].box
        mean = np.array(o.believed_at if o.believed_at is not None else (t.cx, t.cy), dtype=float)
        b.objects[o.name] = ObjectEstimate(o.name, mean, np.eye(2) * o.sigma**2, o.size, first_seen=0)
    return b


def episode(spec: ScenarioSpec, seed: int) -> Episode:
    """A seeded episode of the scenario: true world, initial belief, problem."""
    geom = geometry_of(spec)
    rng = random.Random(f"namo:{spec.name}:{seed}")
    objects = true_objects(spec, geom, rng)
    start = geom.grid.snap(Pt.of(*spec.start))
    goal = geom.grid.snap(Pt.of(*spec.goal))
    if geom.robot_blocked[geom.grid.cell(start)]:
        raise ScenarioError(f"scenario '{spec.name}': start: {list(spec.start)} is too close to a wall")
    if geom.robot_blocked[geom.grid.cell(goal)]:
        raise ScenarioError(f"scenario '{spec.name}': goal: {list(spec.goal)} is too close to a wall")
    for name, p in geom.landmarks:
        if geom.wall_mask[geom.grid.cell(p)]:
            raise ScenarioError(f"scenario '{spec.name}': landmarks.{name}: {p} lies inside a wall")
    world = NamoWorld(geom, start, objects, sensor=spec.sensor, noise=spec.noise, seed=rng.randrange(2**31),
                      params=spec.params)
    belief = initial_belief(spec, geom, objects)

    def estimate(name: str) -> Pt | None:
        est = belief.objects.get(name)
        return None if est is None else est.center

    world.grasp_estimate = estimate
    domain = domain_for(spec.params)
    problem = Problem(domain, {}, belief, Goal.of([atom("RobotAt", goal)], domain.rules), f"namo-{spec.name}-s{seed}")
    desc = spec.description or f"NAMO scenario {spec.name}"
    return Episode(problem, world, belief, f"{desc} (seed {seed}, {len(objects)} objects)")


class ScenarioTable(Mapping[str, Callable[[int], Episode]]):
    """The registry's scenarios: the built-in ones by name, or any ``*.json`` scenario file by path."""

    def __init__(self, builtin: Mapping[str, dict[str, Any]]) -> None:
        self._builtin = dict(builtin)

    def spec(self, name: str) -> ScenarioSpec:
        if name in self._builtin:
            return parse(self._builtin[name], name)
        if name.endswith(".json"):
            if not Path(name).is_file():
                raise ScenarioError(f"no such scenario file: '{name}'")
            return load_file(name)
        raise KeyError(name)

    def __getitem__(self, name: str) -> Callable[[int], Episode]:
        spec = self.spec(name)
        return lambda seed: episode(spec, seed)

    def get(self, name: str, default: Any = None) -> Any:
        try:
            return self[name]
        except KeyError:
            return default

    def __iter__(self) -> Iterator[str]:
        return iter(self._builtin)

    def __len__(self) -> int:
        return len(self._builtin)


SCENARIOS = ScenarioTable(BUILTIN)


def make(name: str, seed: int = 0) -> Episode:
    """The episode of a built-in scenario (or scenario file) for a seed."""
    fn = SCENARIOS.get(name)
    if fn is None:
        raise ScenarioError(f"unknown NAMO scenario '{name}'; valid scenarios: {', '.join(sorted(SCENARIOS))}")
    return fn(seed)  # type: ignore[no-any-return]
