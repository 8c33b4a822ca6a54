"""Scenario descriptions (plain dicts, or JSON files) and their validation.

A scenario names the map (size, walls, landmarks), the robot's start and
goal, the objects (with their true poses; ``known`` ones are in the initial
belief with a prior ``sigma``), optional randomly scattered objects, and
optional sensor (``fov`` in degrees), noise and model parameters.  Every problem is reported as
a :class:`~nowplan.errors.ScenarioError` naming the field at fault, e.g.
``scenario 'fig7': objects[1].size: expected two positive numbers``.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, fields, replace
from pathlib import Path
from typing import Any

from nowplan.domains.namo.params import Noise, Params, Sensor
from nowplan.errors import ScenarioError


@dataclass(frozen=True)
class ObjectSpec:
    name: str
    at: tuple[float, float]
    size: tuple[float, float] = (0.5, 0.5)
    known: bool = False
    sigma: float = 0.05  # prior std of a known object's position
    believed_at: tuple[float, float] | None = None  # prior mean (default: the true position)
    appear_after: int | None = None  # appears before this many actions have run
    jitter: float = 0.0  # seeded uniform displacement of the true position (m)


@dataclass(frozen=True)
class ScatterSpec:
    count: int
    area: tuple[float, float, float, float]  # x0, y0, x1, y1
    size: tuple[float, float] = (0.5, 0.5)
    prefix: str = "obj"
    clearance: float = 0.6  # distance kept from the start and the goal (m)


@dataclass(frozen=True)
class ScenarioSpec:
    name: str
    size: tuple[float, float]
    walls: tuple[tuple[float, float, float, float], ...]
    start: tuple[float, float]
    goal: tuple[float, float]
    objects: tuple[ObjectSpec, ...] = ()
    scatter: tuple[ScatterSpec, ...] = ()
    landmarks: tuple[tuple[str, tuple[float, float]], ...] = ()
    resolution: float = 0.2
    robot_radius: float = 0.25
    fog: bool = True
    sensor: Sensor = Sensor()
    noise: Noise = Noise()
    params: Params = Params()
    description: str = ""
    max_actions: int = 400


class _Reader:
    def __init__(self, scenario: str) -> None:
        self.scenario = scenario

    def fail(self, path: str, msg: str) -> ScenarioError:
        return ScenarioError(f"scenario '{self.scenario}': {path}: {msg}")

    def num(self, v: Any, path: str, positive: bool = False, nonneg: bool = False) -> float:
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(float(v)):
            raise self.fail(path, f"expected a number, got {v!r}")
        f = float(v)
        if positive and f <= 0:
            raise self.fail(path, f"expected a number > 0, got {v!r}")
        if nonneg and f < 0:
            raise self.fail(path, f"expected a number >= 0, got {v!r}")
        return f

    def pair(self, v: Any, path: str, positive: bool = False) -> tuple[float, float]:
        if not isinstance(v, (list, tuple)) or len(v) != 2:
            raise self.fail(path, f"expected two {'positive ' if positive else ''}numbers [x, y], got {v!r}")
        return (self.num(v[0], f"{path}[0]", positive), self.num(v[1], f"{path}[1]", positive))

    def rect(self, v: Any, path: str) -> tuple[float, float, float, float]:
        if not isinstance(v, (list, tuple)) or len(v) != 4:
            raise self.fail(path, f"expected a rectangle [x0, y0, x1, y1], got {v!r}")
        x0, y0, x1, y1 = (self.num(c, f"{path}[{i}]") for i, c in enumerate(v))
        if x1 <= x0 or y1 <= y0:
            raise self.fail(path, f"expected x0 < x1 and y0 < y1, got {list(v)}")
        return (x0, y0, x1, y1)

    def obj(self, d: Any, keys: set[str], path: str) -> dict[str, Any]:
        if not isinstance(d, dict):
            raise self.fail(path, f"expected an object (mapping), got {type(d).__name__}")
        unknown = sorted(set(d) - keys)
        if unknown:
            raise self.fail(f"{path}.{unknown[0]}", f"unknown field; valid fields: {', '.join(sorted(keys))}")
        return d

    def dataclass_fields(self, cls: Any, d: Any, path: str) -> Any:
        names = {f.name: f for f in fields(cls)}
        d = self.obj(d, set(names), path)
        vals: dict[str, Any] = {}
        for k, v in d.items():
            default = getattr(cls(), k)
            if isinstance(default, bool):
                if not isinstance(v, bool):
                    raise self.fail(f"{path}.{k}", f"expected true or false, got {v!r}")
                vals[k] = v
            elif isinstance(default, int):
                vals[k] = int(self.num(v, f"{path}.{k}", nonneg=True))
            else:
                val = self.num(v, f"{path}.{k}", nonneg=True)
                if (k.endswith(("_fail", "_prob")) or k == "miss_prob") and val > 1.0:
                    raise self.fail(f"{path}.{k}", f"a probability must be in [0, 1], got {v!r}")
                vals[k] = math.radians(val) if (cls is Sensor and k == "fov") else val
        return replace(cls(), **vals)


def parse(data: Any, name: str = "scenario") -> ScenarioSpec:
    """Validate a scenario mapping; errors name the field at fault."""
    rd = _Reader(str(data.get("name", name)) if isinstance(data, dict) else name)
    d = rd.obj(data, {f.name for f in fields(ScenarioSpec)}, "scenario")
    for req in ("size", "start", "goal"):
        if req not in d:
            raise rd.fail(req, "missing (required)")
    size = rd.pair(d["size"], "size", positive=True)
    walls = tuple(rd.rect(w, f"walls[{i}]") for i, w in enumerate(_list(rd, d.get("walls", []), "walls")))
    start = rd.pair(d["start"], "start")
    goal = rd.pair(d["goal"], "goal")
    for key, p in (("start", start), ("goal", goal)):
        if not (0 < p[0] < size[0] and 0 < p[1] < size[1]):
            raise rd.fail(key, f"{list(p)} lies outside the map of size {list(size)}")
    objects = []
    seen: set[str] = set()
    okeys = {f.name for f in fields(ObjectSpec)}
    for i, o in enumerate(_list(rd, d.get("objects", []), "objects")):
        path = f"objects[{i}]"
        o = rd.obj(o, okeys, path)
        if "name" not in o or not isinstance(o["name"], str) or not o["name"]:
            raise rd.fail(f"{path}.name", "missing or not a non-empty string")
        if o["name"] in seen:
            raise rd.fail(f"{path}.name", f"'{o['name']}' is used twice")
        seen.add(o["name"])
        if "at" not in o:
            raise rd.fail(f"{path}.at", "missing (required)")
        appear = o.get("appear_after")
        if appear is not None:
            appear = int(rd.num(appear, f"{path}.appear_after", nonneg=True))
        known = o.get("known", False)
        if not isinstance(known, bool):
            raise rd.fail(f"{path}.known", f"expected true or false, got {known!r}")
        objects.append(ObjectSpec(
            name=o["name"], at=rd.pair(o["at"], f"{path}.at"),
            size=rd.pair(o.get("size", [0.5, 0.5]), f"{path}.size", positive=True),
            known=known, sigma=rd.num(o.get("sigma", 0.05), f"{path}.sigma", positive=True),
            believed_at=rd.pair(o["believed_at"], f"{path}.believed_at") if "believed_at" in o else None,
            appear_after=appear, jitter=rd.num(o.get("jitter", 0.0), f"{path}.jitter", nonneg=True),
        ))
    scatter = []
    skeys = {f.name for f in fields(ScatterSpec)}
    for i, s in enumerate(_list(rd, d.get("scatter", []), "scatter")):
        path = f"scatter[{i}]"
        s = rd.obj(s, skeys, path)
        if "count" not in s or "area" not in s:
            raise rd.fail(path, "needs 'count' and 'area'")
        scatter.append(ScatterSpec(
            count=int(rd.num(s["count"], f"{path}.count", nonneg=True)), area=rd.rect(s["area"], f"{path}.area"),
            size=rd.pair(s.get("size", [0.5, 0.5]), f"{path}.size", positive=True),
            prefix=str(s.get("prefix", f"obj{i}_")),
            clearance=rd.num(s.get("clearance", 0.6), f"{path}.clearance", nonneg=True),
        ))
    landmarks = []
    lm = d.get("landmarks", {})
    if not isinstance(lm, dict):
        raise rd.fail("landmarks", "expected a mapping from names to [x, y]")
    for k, v in lm.items():
        landmarks.append((str(k), rd.pair(v, f"landmarks.{k}")))
    fog = d.get("fog", True)
    if not isinstance(fog, bool):
        raise rd.fail("fog", f"expected true or false, got {fog!r}")
    return ScenarioSpec(
        name=str(d.get("name", name)), size=size, walls=walls, start=start, goal=goal,
        objects=tuple(objects), scatter=tuple(scatter), landmarks=tuple(landmarks),
        resolution=rd.num(d.get("resolution", 0.2), "resolution", positive=True),
        robot_radius=rd.num(d.get("robot_radius", 0.25), "robot_radius", positive=True),
        fog=fog,
        sensor=rd.dataclass_fields(Sensor, d.get("sensor", {}), "sensor"),
        noise=rd.dataclass_fields(Noise, d.get("noise", {}), "noise"),
        params=rd.dataclass_fields(Params, d.get("params", {}), "params"),
        description=str(d.get("description", "")),
        max_actions=int(rd.num(d.get("max_actions", 400), "max_actions", positive=True)),
    )


def _list(rd: _Reader, v: Any, path: str) -> list[Any]:
    if not isinstance(v, list):
        raise rd.fail(path, f"expected a list, got {type(v).__name__}")
    return v


def load_file(path: str | Path) -> ScenarioSpec:
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise ScenarioError(f"cannot read scenario file '{p}': {exc.strerror or exc}") from None
    except UnicodeDecodeError:
        raise ScenarioError(f"scenario file '{p}' is not UTF-8 text; give a JSON scenario file "
                            "(docs/namo.md)") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ScenarioError(f"scenario file '{p}': line {exc.lineno}: invalid JSON ({exc.msg})") from None
    return parse(data, p.stem)
