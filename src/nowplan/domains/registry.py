"""Domains register themselves here: scenarios (seeded problem makers) and renderers.

A domain package calls :func:`register` at import time with a
:class:`DomainSpec`.  :func:`get_domain` imports the known domain packages
lazily and gives a :class:`nowplan.errors.ScenarioError` listing the valid
names for an unknown one.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from nowplan.core.domain import Domain, Problem
from nowplan.errors import ScenarioError

# domain packages under nowplan.domains that register a DomainSpec when imported
KNOWN_PACKAGES = ("logistics", "namo", "pieces", "kitchen", "marsupial")


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
    name: str
    description: str
    scenarios: Mapping[str, ScenarioFn]
    renderer: RendererFn | None = None
    default_scenario: str = ""
    demo: DemoFn | None = None  # `nowplan demo NAME` runs this
    extras: Mapping[str, Any] = field(default_factory=dict)

    def scenario(self, name: str) -> ScenarioFn:
        fn = self.scenarios.get(name)
        if fn is None:
            raise ScenarioError(
                f"unknown scenario '{name}' for domain '{self.name}'; "
                f"valid scenarios: {', '.join(sorted(self.scenarios))}"
            )
        return fn


_REGISTRY: dict[str, DomainSpec] = {}


def register(spec: DomainSpec) -> DomainSpec:
    _REGISTRY[spec.name] = spec
    return spec


def _load_all() -> None:
    for pkg in KNOWN_PACKAGES:
        importlib.import_module(f"nowplan.domains.{pkg}")


def domain_names() -> list[str]:
    _load_all()
    return sorted(_REGISTRY)


def get_domain(name: str) -> DomainSpec:
    _load_all()
    spec = _REGISTRY.get(name)
    if spec is None:
        raise ScenarioError(
            f"unknown domain '{name}'; valid domains: {', '.join(sorted(_REGISTRY)) or 'none'}"
        )
    return spec


