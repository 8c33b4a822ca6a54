"""Strategies: named sets of switches for the executive.

A strategy string is one switch name or several joined by ``+`` (for example
``hpn+aggressive``).  Each switch may set strategy or planner fields and add
a mechanism (see :mod:`nowplan.acting.mechanisms`).  Switches of mechanisms
not built yet are refused with a message saying so, never silently ignored.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.mechanisms import SWITCHES, Mechanism, Switch, register_switch
from nowplan.errors import ScenarioError
from nowplan.planning.regression import PlannerConfig

if TYPE_CHECKING:
    from nowplan.core.domain import Domain


# modules that register switches with mechanisms when imported, with the switches each registers:
# a strategy imports only its own switches' modules (the monitor's plan library, RCHPN's reordering
# and the online policy are ~0.1 s of a run's start-up that a plain hpn run does not use);
# tests/test_startup.py checks the names against what the modules register
MECHANISM_MODULES: dict[str, tuple[str, ...]] = {
    "nowplan.acting.aggressive": ("aggressive",),
    "nowplan.acting.flexible": ("flexible",),
    "nowplan.acting.serendipity": ("serendipity",),
    "nowplan.acting.selective": ("selective",),
    "nowplan.acting.peephole": ("peephole",),
    "nowplan.acting.monitor": ("monitor", "monitor-goal", "monitor-restore", "monitor-cost", "monitor-rule-cost"),
    "nowplan.acting.online": ("online", "reuse", "deferred"),
}
ONLINE_SWITCHES = frozenset(MECHANISM_MODULES["nowplan.acting.online"])  # run by the online policy


@dataclass(frozen=True)
class Strategy:
    """A parsed strategy (:func:`parse_strategy`): its switches, budgets and planner settings."""

    name: str = "hpn"
    switches: tuple[str, ...] = ("hpn",)
    hierarchical: bool = True  # plan over criticality levels (False: flat, every step primitive)
    foresight: bool = False  # planner and generators see the whole plan stack (seed 000 III-B)
    cost_increase: float = 0.25  # selective: replan when a plan's remaining cost grows by this fraction
    planner: PlannerConfig = field(default_factory=PlannerConfig)
    max_actions: int = 1_000  # executive budgets: no loop without a bound
    max_plans: int = 2_000  # planner calls the strategy makes of its own accord
    # planner calls allowed on top of max_plans for each surprise (failed action or exogenous change):
    # replanning after the world's doing is bounded by the action budget, not by max_plans alone
    replans_per_surprise: int = 4
    max_depth: int = 64
    max_refinements: int = 5  # refinements of one plan step without an action before it is given up
    max_cycles: int = 3  # progress guard: cycles (nowplan.acting.progress) before a run ends as a livelock
    max_stalls: int = 25  # progress guard: failures in a row that leave the situation unchanged
    max_retries: int = 2  # flexible: setbacks a plan may retry before it is replanned (Fig. 4)
    refine_flat: bool = False  # a plan whose step cannot be refined is replaced by a concrete plan
    # where the run would end because the root's abstract plans make no progress, plan the root goal
    # concretely once instead (acting/refine_flat.py, FlatSteps.last_resort; off: the nofallback switch)
    last_resort: bool = True
    # goal atoms an abstract plan leaves alone are owed only at its end (acting/postpone.py; off: the
    # maintain switch, the seed's exactly regressed pre-images)
    postpone: bool = True
    domain_planner: bool = False  # plan with the domain's own planner (Domain.planner) when it has one
    direct_refinements: bool = True  # short refinements made without a planner call (acting/refine.py)
    time_limit: float = 600.0

    def exhausted(self, metrics: Metrics, elapsed: float) -> tuple[Outcome, str] | None:
        """The budget that has run out, as ``(LIMIT, reason)``, or None.

        The reason says what the world did meanwhile (failed actions, exogenous changes, cycles),
        so a run a budget ended is told apart from a livelock (which ends sooner, as such).
        """
        why = f" ({metrics.world_summary()})"
        if metrics.actions >= self.max_actions:
            return Outcome.LIMIT, f"action budget of {self.max_actions} spent" + why
        plan_budget = self.plan_budget(metrics)
        if metrics.plans_made + metrics.plan_failures >= plan_budget:
            return Outcome.LIMIT, f"planning budget of {plan_budget} calls spent" + why
        if elapsed > self.time_limit:
            return Outcome.LIMIT, f"time limit of {self.time_limit:g} s reached" + why
        return None

    def plan_budget(self, metrics: Metrics) -> int:
        """Planner calls allowed so far: ``max_plans`` plus ``replans_per_surprise`` for each failed
        action and exogenous change (the world's surprises: a run at a 70 % failure rate replans
        after most actions, which a fixed count would end by its budget while it is progressing;
        the sum stays bounded, as surprises are bounded by the action budget)."""
        surprises = metrics.failed_actions + metrics.exogenous_changes
        return self.max_plans + self.replans_per_surprise * surprises

    def mechanisms(self) -> list[Mechanism]:
        _load(self.switches)
        out: list[Mechanism] = []
        for s in self.switches:
            sw = SWITCHES[s]
            if sw.mechanism is not None:
                out.append(sw.mechanism(self))
        return out

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "switches": list(self.switches),
            "hierarchical": self.hierarchical,
            "foresight": self.foresight,
            "serialization": self.planner.serialization,
            "monotonic": self.planner.monotonic,
            "max_actions": self.max_actions,
            "domain_planner": self.domain_planner,
            "refine_flat": self.refine_flat,
            "last_resort": self.last_resort,
            "postpone": self.postpone,
            "direct_refinements": self.direct_refinements,
        }


register_switch(Switch("hpn", "hierarchical planning over criticality levels", {"hierarchical": True}))
register_switch(Switch("flat", "no hierarchy: plan every step concretely (a full search that spends its nodes "
                        "searches once more with weight 5)", {"hierarchical": False}, planner={"retry_weight": 5.0}))
register_switch(
    Switch("foresight", "planner and generators see the plan stack (taboo regions, shadows)",
           {"foresight": True})
)
register_switch(
    Switch("noshortcuts", "full backward search only (no serialization or monotonic tries)",
           planner={"serialization": False, "monotonic": False})
)

register_switch(
    Switch("refine-flat", "when a step of an abstract plan cannot be refined, plan that plan's goal "
           "concretely (for hierarchies without the downward refinement property, e.g. --criticality auto)",
           {"refine_flat": True})
)
register_switch(
    Switch("regroup", "reorder each abstract plan so that consecutive steps need the same values of the "
           "preconditions their level hides (planning/regroup.py; on with --criticality auto)",
           planner={"regroup": True})
)
register_switch(
    Switch("noregroup", "keep each abstract plan in the planner's order (--criticality auto regroups otherwise)",
           planner={"regroup": False})
)
register_switch(
    Switch("noprune", "keep the regression engine's plans as found (no elimination of the steps the rest does "
           "not need, planning/prune.py): the ablation", planner={"prune": False})
)
register_switch(
    Switch("h2", "regression drops subgoals holding two facts no reachable state holds together "
           "(planning/h2.py: h² mutexes of the concrete problem, sound at every level); on by default "
           "with flat, off with hpn", planner={"h2": True})
)
register_switch(
    Switch("noh2", "no h² pruning of regression's subgoals, also where the strategy plans flat (the ablation)",
           planner={"h2": False})
)
register_switch(
    Switch("nofallback", "no last resort: where the root's abstract plans make no progress (a hierarchy "
           "that is not downward refinable), give up as the seed's HPN does instead of planning the "
           "root goal concretely", {"last_resort": False})
)
register_switch(
    Switch("maintain", "keep every goal atom in every pre-image of an abstract plan, as the seed's HPN does "
           "(no postponing of the atoms its steps leave alone to its last step, acting/postpone.py)",
           {"postpone": False})
)
register_switch(
    Switch("nodirect", "refine every abstract step with a planner call (no direct refinements of at "
           "most 4 steps, acting/refine.py): the ablation of that shortcut", {"direct_refinements": False})
)
register_switch(
    Switch("domain-planner", "plan with the domain's own planner (e.g. pieces' means-ends rule)",
           {"domain_planner": True})
)


def is_online(strategy: Strategy) -> bool:
    """The strategy runs under seed 004's online policy (:mod:`nowplan.acting.online`), not the executive."""
    return bool(ONLINE_SWITCHES & set(strategy.switches))


def check_supported(domain: Domain, strategy: Strategy) -> None:
    """Refuse, before a run starts, a switch the domain declares it cannot support (and why)."""
    for switch in strategy.switches:
        why = domain.unsupported.get(switch)
        if why is not None:
            fix = (f"drop '{switch}' from the strategy '{strategy.name}'" if len(strategy.switches) > 1
                   else "choose another strategy (e.g. hpn)")
            raise ScenarioError(f"strategy switch '{switch}' does not apply to domain {domain.name}: {why}; {fix}")


# switches whose mechanisms arrive with later work; named so users are told plainly
PLANNED: dict[str, str] = {}


def _load(switches: tuple[str, ...] | list[str] | None = None) -> None:
    """Import the mechanism modules that register ``switches`` (None: all of them)."""
    for module, names in MECHANISM_MODULES.items():
        if switches is None or any(n in names for n in switches):
            importlib.import_module(module)


def strategy_names() -> list[str]:
    """The strategy switches (``hpn``, ``flat``, ``online``, ``peephole``, ...) a strategy string may join with '+'
    (the mechanism modules' switches by name, without importing them)."""
    return sorted({*SWITCHES, *(n for names in MECHANISM_MODULES.values() for n in names)})


# switches that contradict each other: at most one of each group, with why
EXCLUSIVE: tuple[tuple[frozenset[str], str], ...] = (
    (frozenset({"hpn", "flat"}), "hpn plans over criticality levels, flat plans every step concretely"),
    (frozenset({"aggressive", "selective"}),
     "aggressive replans after every action, selective only when a trigger fires"),
    (frozenset({"monitor", "monitor-goal", "monitor-restore", "monitor-cost", "monitor-rule-cost"}),
     "each monitor-* switch is a different replanning rule of the same monitor"),
    (frozenset({"online", "aggressive"}), "the online policy already replans after every action"),
)


def _check_compatible(parts: list[str]) -> None:
    seen: set[str] = set()
    for p in parts:
        if p in seen:
            raise ScenarioError(f"strategy switch '{p}' is named twice; name each switch once")
        seen.add(p)
    for group, why in EXCLUSIVE:
        both = [p for p in parts if p in group]
        if len(both) > 1:
            raise ScenarioError(
                f"strategy switches {' and '.join(repr(b) for b in both)} contradict each other ({why}); "
                "keep one"
            )


def parse_strategy(spec: str, *, base_planner: PlannerConfig | None = None, **overrides: Any) -> Strategy:
    """``"hpn+aggressive"`` -> a :class:`Strategy`; unknown names list the valid ones.

    ``base_planner`` (e.g. a domain's own settings, ``DomainSpec.planner``) is the planner
    configuration the switches then modify; without it the engine's defaults.
    """
    parts = [p.strip() for p in spec.split("+") if p.strip()]
    _load(parts)
    if not parts:
        raise ScenarioError(f"empty strategy; valid strategies: {', '.join(strategy_names())}")
    s = Strategy(name=spec, switches=tuple(parts))
    if base_planner is not None:
        s = replace(s, planner=base_planner)
    for part in parts:
        sw = SWITCHES.get(part)
        if sw is None and part in PLANNED:
            raise ScenarioError(
                f"strategy switch '{part}' ({PLANNED[part]}) is not implemented yet; "
                f"available: {', '.join(strategy_names())}"
            )
        if sw is None:
            raise ScenarioError(
                f"unknown strategy '{part}'; valid strategies: {', '.join(strategy_names())} "
                "(combine with '+', e.g. hpn+aggressive)"
            )
        if sw.fields:
            s = replace(s, **dict(sw.fields))
        if sw.planner:
            s = replace(s, planner=replace(s.planner, **dict(sw.planner)))
    _check_compatible(parts)
    if overrides:
        s = replace(s, **overrides)
    if s.planner.h2 is None:  # h² pruning where the strategy plans flat (the `h2` / `noh2` switches decide otherwise)
        s = replace(s, planner=replace(s.planner, h2=not s.hierarchical))
    return s
