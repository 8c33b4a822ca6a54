"""Strategies: named sets of switches for the executive.

A strategy string is one base name or several joined by ``+`` (for example
``hpn+aggressive``); each name turns on its switches.  Switches that belong
to mechanisms not built yet are refused with a message saying so, never
silently ignored.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

from nowplan.errors import ScenarioError
from nowplan.planning.regression import PlannerConfig


@dataclass(frozen=True)
class Strategy:
    name: str = "hpn"
    hierarchical: bool = True  # plan over criticality levels (False: flat, every step primitive)
    aggressive: bool = False  # replan after every action
    planner: PlannerConfig = field(default_factory=PlannerConfig)
    max_actions: int = 1_000  # executive budgets: no loop without a bound
    max_plans: int = 2_000
    max_depth: int = 64
    time_limit: float = 600.0

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "hierarchical": self.hierarchical,
            "aggressive": self.aggressive,
            "serialization": self.planner.serialization,
            "monotonic": self.planner.monotonic,
            "max_actions": self.max_actions,
        }


_SWITCHES: dict[str, dict[str, Any]] = {
    "hpn": {"hierarchical": True},
    "flat": {"hierarchical": False},
    "aggressive": {"aggressive": True},
    "noshortcuts": {"planner": ("serialization", False, "monotonic", False)},
}

# switches whose mechanisms arrive with later work; named so users are told plainly
PLANNED = {
    "flexible": "flexible execution (seed 000 Fig. 4)",
    "serendipity": "serendipity (seed 000 Fig. 5)",
    "selective": "selective replanning triggers (seed 000 Fig. 5)",
    "foresight": "foresight (seed 000)",
    "peephole": "RCHPN peephole optimization (seed 002)",
    "monitor": "expected-vs-observed monitor with a plan library (seed 003)",
    "reuse": "reuse-enforced replanning (seed 004)",
    "deferred": "deferred sampling (seed 004)",
}


def strategy_names() -> list[str]:
    return sorted(_SWITCHES)


def parse_strategy(spec: str, **overrides: Any) -> Strategy:
    """``"hpn+aggressive"`` -> a :class:`Strategy`; unknown names list the valid ones."""
    s = Strategy(name=spec)
    for part in [p.strip() for p in spec.split("+") if p.strip()]:
        if part in PLANNED:
            raise ScenarioError(
                f"strategy switch '{part}' ({PLANNED[part]}) is not implemented yet; "
                f"available: {', '.join(strategy_names())}"
            )
        sw = _SWITCHES.get(part)
        if sw is None:
            raise ScenarioError(
                f"unknown strategy '{part}'; valid strategies: {', '.join(strategy_names())} "
                "(combine with '+', e.g. hpn+aggressive)"
            )
        for k, v in sw.items():
            if k == "planner":
                pairs = dict(zip(v[::2], v[1::2], strict=True))
                s = replace(s, planner=replace(s.planner, **pairs))
            else:
                s = replace(s, **{k: v})
    if overrides:
        s = replace(s, **overrides)
    return s
