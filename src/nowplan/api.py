"""Everything a domain author needs, in one import: ``from nowplan import api``.

A domain is a Python package that defines a :class:`DomainSpec` and is
installed as a plugin (an entry point in the group ``nowplan.domains``) or
named with ``NOWPLAN_DOMAINS=module`` / ``nowplan --import module``.
``docs/writing-a-domain.md`` builds one step by step; the names here are
what it uses.

**The model** (what the agent knows)

* :class:`Var`, :func:`atom` / :class:`Atom`, :class:`Goal` — terms, atoms
  (``atom("at", "cup", "kitchen")``; ``value=False`` for a negative literal)
  and goals (``Goal.of(atoms, domain.rules)``).
* :class:`Predicate` — name, arity, argument types; optionally a ``test``
  (a function of the belief) and a :class:`ValueRule` for non-boolean fluents
  (:class:`ToleranceRule`, :class:`AtLeastRule`).
* :class:`Operator` with :class:`Precondition` ``(atom, criticality)`` —
  a higher criticality is considered at a more abstract level (HPN); the top
  level keeps only the highest class, and each refinement of a step adds the
  next class down (``docs/engine.md``).  :func:`static` marks a precondition on
  a predicate no operator changes: it needs no criticality.  Operators may
  declare :class:`Resource` uses (:class:`ResourceUse`) for the peephole and
  :class:`Generator` s that bind "choose" variables.
* Conflict rules for ``Domain(conflicts=…)``: :func:`at_most_one`,
  :func:`exactly_one`, :func:`excludes` — what can never hold together, so
  the planner prunes impossible subgoals.
* :class:`Domain` (predicates, operators, types, conflicts, triggers, an own
  planner, unsupported switches) and :class:`Problem` (objects, initial
  belief or :class:`State`, goal).

**The world and the belief** (what happens, and what the agent believes)

* :class:`SimulatedWorld` — base of simulated worlds: fault injection
  (``failure_prob``, ``exogenous_prob``) as constructor options, ``refuse``,
  ``apply``, ``fault`` (a domain's own fault), ``exogenous_change``.
  :class:`SymbolicWorld` is one over a :class:`State`.  A real robot
  implements :class:`World` (``execute(action) -> Observation``).  A world
  that can tell its true state (:class:`Inspectable`: ``true_state()``,
  something the domain's predicates can test; a ``SymbolicWorld`` does)
  has success judged in the world, not the belief.
* :class:`Belief` (``update(action, observation)``) and its optional
  capabilities, each a ``Protocol`` checked once when a run starts:
  :class:`HasValues`, :class:`ListsFacts`, :class:`HasState`,
  :class:`Reobserves`, :class:`HasStreams`, :class:`HasHeuristic`,
  :class:`AfterAction`, :class:`Fingerprinted` (the progress guard's "same
  situation"), :class:`HasUnknowns` (fluents known neither way: neither they
  nor their negations hold).  Bases: :class:`SymbolicBelief` (an observed symbolic state that lists its facts) and :class:`ParticleBelief`
  (weighted sampled states).

**The plugin**

* :class:`DomainSpec` — name, description, scenarios (``seed -> Episode``),
  renderer, demo, the matrix test's scenario; :class:`Episode` — problem,
  world and belief of one run.

**Running**

* :func:`run_episode` with :func:`parse_strategy` (``"hpn"``, ``"flat"``,
  ``"online+reuse"``, …; :func:`strategy_names`) gives :class:`Metrics`
  with an :class:`Outcome`; :class:`Trace` records a run as JSONL.
* :func:`plan` with :class:`PlannerConfig` plans once (a :class:`PlanResult`).  Without
  ``levels`` it plans at the domain's *top* (most abstract) level, as the executive's first call
  does; pass ``levels=flat_levels()`` for a concrete plan (every precondition counts) or a
  :class:`LevelMap` for one level of the hierarchy.
* Errors: :class:`NowplanError`, :class:`ModelError`, :class:`ScenarioError`.
"""

from __future__ import annotations

from nowplan.acting.metrics import Metrics, Outcome
from nowplan.acting.progress import Fingerprinted
from nowplan.acting.monitor_support import MonitorSupport
from nowplan.acting.resources import ResourceModel
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import Strategy, parse_strategy, strategy_names
from nowplan.belief.particle_belief import ParticleBelief
from nowplan.belief.protocols import (
    AfterAction,
    HasHeuristic,
    HasState,
    HasStreams,
    HasUnknowns,
    HasValues,
    ListsFacts,
    Reobserves,
    capabilities,
    check_belief,
)
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.core.atoms import (
    AtLeastRule,
    AtMostOne,
    Atom,
    Excludes,
    Goal,
    ToleranceRule,
    ValueRule,
    Var,
    at_most_one,
    atom,
    exactly_one,
    excludes,
)
from nowplan.core.domain import Domain, Predicate, Problem
from nowplan.core.operators import (
    Action,
    Generator,
    Operator,
    Precondition,
    Resource,
    ResourceUse,
    StateFreeCost,
    reads_nothing,
    static,
)
from nowplan.core.levels import LevelMap, flat_levels
from nowplan.core.state import State
from nowplan.domains.registry import DomainSpec, Episode, ScenarioFn
from nowplan.errors import ModelError, NowplanError, ScenarioError
from nowplan.planning.plan import PlanResult, PlanStatus
from nowplan.planning.regression import PlannerConfig, plan
from nowplan.trace import Trace
from nowplan.worlds.base import Belief, FaultInjection, Inspectable, Observation, SimulatedWorld, World
from nowplan.worlds.symbolic import SymbolicWorld

__all__ = [
    # the model
    "Var", "Atom", "atom", "Goal", "ValueRule", "ToleranceRule", "AtLeastRule",
    "Predicate", "Operator", "Precondition", "static", "Resource", "ResourceUse", "Generator",
    "reads_nothing", "Action", "at_most_one", "exactly_one", "excludes", "AtMostOne", "Excludes",
    "Domain", "Problem", "State",
    # the world and the belief
    "World", "SimulatedWorld", "SymbolicWorld", "FaultInjection", "Inspectable", "Observation",
    "Belief", "SymbolicBelief", "ParticleBelief", "HasValues", "ListsFacts", "HasState", "Reobserves",
    "HasStreams", "HasUnknowns", "HasHeuristic", "AfterAction", "Fingerprinted", "capabilities", "check_belief",
    # the plugin
    "DomainSpec", "Episode", "ScenarioFn", "ResourceModel", "MonitorSupport",
    # running
    "run_episode", "parse_strategy", "strategy_names", "Strategy", "Metrics", "Outcome", "Trace",
    "plan", "PlannerConfig", "PlanResult", "PlanStatus", "LevelMap", "flat_levels", "StateFreeCost",
    # errors
    "NowplanError", "ModelError", "ScenarioError",
]
