"""Domains as plugins: where nowplan finds each :class:`DomainSpec`.

A domain is found, the built-in ones included, in one of two ways:

* an entry point in the group ``nowplan.domains`` of an installed package
  (its pyproject names it: ``[project.entry-points."nowplan.domains"]
  house = "house_domain:SPEC"``); nowplan's own domains are declared so in
  nowplan's pyproject;
* a module named in the environment variable ``NOWPLAN_DOMAINS``
  (``NOWPLAN_DOMAINS=house_domain,lab.domain``) or with ``nowplan --import
  MOD``; the module's ``SPEC`` (a :class:`DomainSpec`) is used.

Discovery runs once, on the first lookup; a module that cannot be imported
or has no ``SPEC`` is an error naming it and the fix.  :func:`register`
adds a spec by hand (a script's own domain, tests).  :func:`get_domain`
gives a :class:`nowplan.errors.ScenarioError` listing the valid names for
an unknown one.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from nowplan.core.domain import Domain, Problem
from nowplan.errors import ScenarioError

if TYPE_CHECKING:
    from nowplan.experiments.reproductions import Reproduction
    from nowplan.planning.regression import PlannerConfig

ENTRY_POINT_GROUP = "nowplan.domains"
ENV_VAR = "NOWPLAN_DOMAINS"


@dataclass
class Episode:
    """Everything one run needs: the agent's model and belief, and the true world."""

    problem: Problem
    world: Any  # nowplan.worlds.base.World
    belief: Any  # the agent's belief (its own object, never the world's state)
    description: str = ""


ScenarioFn = Callable[[int], Episode]  # seed -> episode
RendererFn = Callable[[Any, Any], bytes]  # (world, belief) -> PNG bytes
DemoFn = Callable[[Any], int]  # parsed `nowplan demo` arguments -> exit code


@dataclass
class DomainSpec:
    """Everything a domain provides, found by discovery (no registry keyed by name elsewhere).

    What the engine needs while planning and acting travels on the ``model``
    (:class:`nowplan.core.domain.Domain`: operators, conflict rules, triggers,
    its own planner, resource model, monitor support); the spec adds what
    the command line and the tests need: ``scenarios`` (name -> ``seed ->
    Episode``), a ``renderer`` for frames, a ``demo``, the paper
    ``reproductions`` it runs, and the small ``matrix_scenario`` that the
    strategy-matrix test runs under every strategy.
    """

    name: str
    description: str
    scenarios: Mapping[str, ScenarioFn]
    renderer: RendererFn | None = None
    default_scenario: str = ""
    demo: DemoFn | None = None  # `nowplan demo NAME` runs this
    extras: Mapping[str, Any] = field(default_factory=dict)
    # the small seeded scenario the strategy-matrix test runs (default: default_scenario), and
    # whether that run is slow (then the matrix marks it @slow)
    matrix_scenario: str = ""
    matrix_slow: bool = False
    reproductions: tuple[Reproduction, ...] = ()  # `nowplan reproduce SEED` runs these
    # the model, when one Domain serves every scenario (a domain built per map, like marsupial's,
    # leaves it None: each Episode's problem carries its own)
    model: Domain | None = None
    # the domain's planner settings, the base that
    # `nowplan run`, sweeps and reproductions start from before the strategy's switches apply;
    # None: the engine's defaults
    planner: PlannerConfig | None = None
    source: str = ""  # where it was found: an entry point or a module (set by discovery)

    def scenario(self, name: str) -> ScenarioFn:
        fn = self.scenarios.get(name)
        if fn is None:
            raise ScenarioError(
                f"unknown scenario '{name}' for domain '{self.name}'; "
                f"valid scenarios: {', '.join(sorted(self.scenarios))}"
            )
        return fn


_REGISTRY: dict[str, DomainSpec] = {}
_DISCOVERED = False


def register(spec: DomainSpec) -> DomainSpec:
    _REGISTRY[spec.name] = spec
    return spec


def _add(obj: Any, source: str) -> None:
    if not isinstance(obj, DomainSpec):
        raise ScenarioError(
            f"{source} gives {type(obj).__name__}, not a nowplan DomainSpec; point it at the module's "
            "DomainSpec (e.g. 'my_domain:SPEC')"
        )
    if not obj.source:
        obj.source = source
    _REGISTRY[obj.name] = obj


def load_module(name: str) -> None:
    """Import a domain module and add its ``SPEC`` (``NOWPLAN_DOMAINS`` and ``--import``)."""
    try:
        mod = importlib.import_module(name)
    except ImportError as exc:
        raise ScenarioError(
            f"cannot import domain module '{name}' ({exc}); install its package or put it on PYTHONPATH"
        ) from exc
    spec = getattr(mod, "SPEC", None)
    if spec is None:
        raise ScenarioError(f"domain module '{name}' has no SPEC; define SPEC = DomainSpec(...) in it")
    _add(spec, f"module {name}")


def _discover() -> None:
    global _DISCOVERED
    if _DISCOVERED:
        return
    from importlib.metadata import entry_points

    for ep in sorted(entry_points(group=ENTRY_POINT_GROUP), key=lambda e: e.name):
        try:
            obj = ep.load()
        except ImportError as exc:
            raise ScenarioError(
                f"the domain plugin '{ep.name}' ({ep.value}) cannot be imported: {exc}; "
                "reinstall its package or uninstall it"
            ) from exc
        _add(obj, f"entry point {ep.name} = {ep.value}")
    for name in filter(None, (m.strip() for m in os.environ.get(ENV_VAR, "").split(","))):
        load_module(name)
    _DISCOVERED = True


def domain_names() -> list[str]:
    _discover()
    return sorted(_REGISTRY)


def get_domain(name: str) -> DomainSpec:
    _discover()
    spec = _REGISTRY.get(name)
    if spec is None:
        raise ScenarioError(
            f"unknown domain '{name}'; valid domains: {', '.join(sorted(_REGISTRY)) or 'none'}"
            f" (a domain of your own: an entry point in '{ENTRY_POINT_GROUP}' or {ENV_VAR}=your.module)"
        )
    return spec
