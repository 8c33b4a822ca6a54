"""Fault levels for sweeps: a scenario name with knobs, ``small?failure=0.5&exogenous=0.25``.

A sweep's configuration is (domain, scenario, strategy, seed); a fault level
rides on the scenario name, so run keys, the store and the reports need no
new column and a fault benchmark resumes like any sweep.  The knobs:

==============  ==========================================================
``failure``     probability that an action fails in the world (``world.failure_prob``, or a
                NAMO world's ``noise.move_fail`` and ``noise.grasp_fail``)
``exogenous``   probability of an exogenous change after an action (``world.exogenous_prob``)
``sigma_per_m`` range-dependent sensor noise (m per m; the world's and the agent's sensor model)
``sigma``       sensor noise at 0 m or independent of range (m; a NAMO sensor's ``sigma0``,
                a particle sensor's ``sigma``, e.g. the kitchen's)
``miss``        probability that a visible object goes undetected on one look (``miss_prob``,
                or a particle sensor's false-negative rate ``p_fn``, e.g. the kitchen's)
==============  ==========================================================

A knob the episode's world does not have is refused with a
:class:`~nowplan.errors.ScenarioError` naming it (never silently ignored).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from typing import Any

from nowplan.errors import NowplanError, ScenarioError

SEP = "?"
# knob -> attribute on the world
_WORLD = {"failure": "failure_prob", "exogenous": "exogenous_prob"}
# knob -> the attributes of world.sensor it may set, the first the sensor has
_SENSOR = {"sigma_per_m": ("sigma_per_m",), "sigma": ("sigma0", "sigma"), "miss": ("miss_prob", "p_fn")}
# a world without failure_prob whose ``noise`` has these rates (NAMO: moves stop early, grasps miss)
_NOISE_FAILURE = ("move_fail", "grasp_fail")
KNOBS = (*_WORLD, *_SENSOR)


@dataclass(frozen=True)
class Faults:
    failure: float = 0.0
    exogenous: float = 0.0
    sigma_per_m: float | None = None  # None: the scenario's own sensor noise
    miss: float | None = None
    sigma: float | None = None

    def items(self) -> list[tuple[str, float]]:
        out: list[tuple[str, float]] = []
        for f in fields(self):
            v = getattr(self, f.name)
            if v is not None and (v != 0.0 or f.name in _SENSOR):
                out.append((f.name, float(v)))
        return out

    def label(self) -> str:
        """``failure=0.5&exogenous=0.25`` (empty when there are no faults)."""
        return "&".join(f"{k}={v:g}" for k, v in self.items())

    def scenario(self, base: str) -> str:
        """The scenario name that carries these faults."""
        lab = self.label()
        return f"{base}{SEP}{lab}" if lab else base


def split_scenario(name: str) -> tuple[str, Faults]:
    """``"small?failure=0.5"`` -> ``("small", Faults(failure=0.5))``; bad knobs -> ScenarioError."""
    if SEP not in name:
        return name, Faults()
    base, _, query = name.partition(SEP)
    values: dict[str, float] = {}
    for part in (p for p in query.split("&") if p):
        key, eq, raw = part.partition("=")
        if not eq or key not in KNOBS:
            raise ScenarioError(
                f"scenario '{name}': fault '{part}' is not KNOB=VALUE with a knob among {', '.join(KNOBS)}")
        try:
            v = float(raw)
        except ValueError:
            raise ScenarioError(f"scenario '{name}': fault {key}: '{raw}' is not a number") from None
        top = 10.0 if key in ("sigma_per_m", "sigma") else 1.0
        if not 0.0 <= v <= top:
            what = {"sigma_per_m": "noise per metre", "sigma": "noise in metres"}.get(key, "probability")
            raise ScenarioError(f"scenario '{name}': fault {key}={raw} is out of range; give a {what} "
                                f"in [0, {top:g}]")
        values[key] = v
    return base, Faults(**values)


def apply_faults(episode: Any, faults: Faults) -> None:
    """Set the fault knobs on a freshly made episode's world (and, for the sensor, the agent's model)."""
    world, belief = episode.world, episode.belief
    for knob, attr in _WORLD.items():
        v = getattr(faults, knob)
        if not v:
            continue
        if knob == "failure" and not hasattr(world, attr) and _noise_failure(world):
            world.noise = replace(world.noise, **{k: v for k in _NOISE_FAILURE})
            continue
        if not hasattr(world, attr):
            raise ScenarioError(f"fault '{knob}': this domain's world has no {attr}; drop it for this domain")
        if knob == "exogenous" and getattr(world, "exogenous", True) is None:
            raise ScenarioError(f"fault '{knob}': this world has no exogenous changes to make; drop it")
        setattr(world, attr, v)
    for knob in _SENSOR:
        v = getattr(faults, knob)
        if v is None:
            continue
        sensor: Any = getattr(world, "sensor", None)
        name = _sensor_attr(sensor, knob)
        if sensor is None or name is None:
            raise ScenarioError(f"fault '{knob}': this domain's world has no sensor with "
                                f"{' or '.join(_SENSOR[knob])}; drop it")
        try:
            world.sensor = replace(sensor, **{name: v})
            if hasattr(belief, "sensor"):  # the agent's model of its sensor is the sensor
                belief.sensor = replace(belief.sensor, **{name: v})
        except (ValueError, NowplanError) as exc:  # the sensor's own range check (e.g. p_fn < 1)
            raise ScenarioError(f"fault {knob}={v:g}: {exc}") from None


def supports(episode: Any, knob: str) -> bool:
    """Does the episode's world have this fault knob?"""
    world = episode.world
    if knob == "failure" and _noise_failure(world):
        return True
    if knob in _WORLD:
        ok = hasattr(world, _WORLD[knob])
        return ok and not (knob == "exogenous" and getattr(world, "exogenous", True) is None)
    return _sensor_attr(getattr(world, "sensor", None), knob) is not None


def _sensor_attr(sensor: Any, knob: str) -> str | None:
    """The attribute of ``sensor`` that the knob sets, or None."""
    if sensor is None:
        return None
    return next((a for a in _SENSOR[knob] if hasattr(sensor, a)), None)


def _noise_failure(world: Any) -> bool:
    noise = getattr(world, "noise", None)
    return noise is not None and all(hasattr(noise, k) for k in _NOISE_FAILURE)
