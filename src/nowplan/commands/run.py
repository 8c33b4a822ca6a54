"""``nowplan run``: run a problem with the executive and write its trace."""

from __future__ import annotations

import argparse
import json
from dataclasses import replace
from collections.abc import Sized
from pathlib import Path
from typing import Any

from nowplan.acting.run import run_episode
from nowplan.acting.strategy import Strategy, parse_strategy, strategy_names
from nowplan.commands.plan import FORWARD_NODES
from nowplan.commands.common import (
    criticality_arg, existing_file, nonneg_int, positive_float, positive_int, probability,
)
from nowplan.core.domain import Domain
from nowplan.domains.registry import Episode, get_domain
from nowplan.errors import UsageError
from nowplan.trace import Trace
from nowplan.tree import render_text


def register(sub: Any) -> None:
    p = sub.add_parser(
        "run",
        help="run a problem with the executive (plan, act, observe, replan) and write a trace",
        description=(
            "Run a registered domain scenario (--domain/--scenario) or a PDDL problem "
            "(DOMAIN.pddl PROBLEM.pddl [--criticality FILE]) in a simulated world."
        ),
    )
    p.add_argument("pddl", nargs="*", type=existing_file, help="DOMAIN.pddl PROBLEM.pddl (optional)")
    p.add_argument("--domain", help="a registered domain, e.g. logistics")
    p.add_argument("--scenario", help="a scenario of the domain (default: the domain's default)")
    p.add_argument("--criticality", type=criticality_arg, metavar="FILE|auto",
                   help="criticality side file for PDDL input, or 'auto': derive the hierarchy from the "
                        "domain, with reachability statics, goal stages and the refine-flat switch "
                        "(see docs/pddl.md)")
    p.add_argument(
        "--strategy", default="hpn",
        help=f"strategy switches joined by '+' (available: {', '.join(strategy_names())})",
    )
    p.add_argument("--seed", type=nonneg_int, default=0, help="seed for every random choice")
    p.add_argument("--failure-prob", type=probability, help="probability that an action fails in the world")
    p.add_argument("--exogenous-prob", type=probability, help="probability of an exogenous change after an action")
    p.add_argument("--max-actions", type=nonneg_int, help="action budget (default: the strategy's 1,000; a PDDL run: "
                   "1,000 or 10 per object, whichever is more)")
    p.add_argument("--time-limit", type=positive_float, help="wall-clock budget for the whole run (s)")
    p.add_argument("--max-nodes", type=positive_int, metavar="N",
                   help="node expansions allowed to each planner call (default: the domain's planner, "
                        "else 50000; a PDDL run's forward searches for the whole goal get nowplan plan's "
                        "20000000, ended by the time limit); raise it when a run fails with 'expanded N "
                        "nodes without a plan'")
    p.add_argument("--trace", type=Path, help="write the JSONL trace here")
    p.add_argument(
        "--frames", type=nonneg_int, nargs="?", const=1, default=0, metavar="EVERY",
        help="with --trace: add the domain's rendered frames to the trace, one every EVERY actions "
        "(default 1), for `nowplan view`",
    )
    p.add_argument("--tree", action="store_true", help="print the plan tree")
    p.add_argument("--json", action="store_true", help="print the metrics as JSON")
    p.set_defaults(func=main)


ACTIONS_PER_OBJECT = 10  # the default action budget of a PDDL run grows with its problem


def pddl_action_budget(objects: Sized, floor: int) -> int:
    """The action budget of a PDDL run the user gave none for: ``floor`` (the strategy's default), or
    10 actions per object where that is more, so a large problem (gripper with 300 balls needs 900+
    actions) is not cut by a budget sized for small ones; the progress guard, not this bound,
    ends a run that loops."""
    return max(floor, ACTIONS_PER_OBJECT * len(objects))


def axiom_strategy(domain: Domain, strategy: Strategy) -> Strategy:
    """The strategy for a domain whose derived predicates are evaluated by rules: its planner calls
    search forward at every level (the regression search cannot regress through a derived atom:
    ``axioms_refusal``); a planner set to regress is refused in one line."""
    if strategy.planner.engine == "regression":
        from nowplan.planning.regression import axioms_refusal

        raise UsageError(f"{axioms_refusal(domain)}; drop the switch that sets the regression engine")
    if strategy.planner.engine == "auto":
        strategy = replace(strategy, planner=replace(strategy.planner, engine="forward"))
    return strategy


def build_episode(args: argparse.Namespace, hierarchical: bool = True) -> Episode:
    if args.pddl:
        if args.domain:
            raise UsageError("give either DOMAIN.pddl PROBLEM.pddl or --domain, not both")
        if len(args.pddl) != 2:
            raise UsageError("expected two files: DOMAIN.pddl PROBLEM.pddl")
        from nowplan.belief.symbolic import SymbolicBelief
        from nowplan.io.pddl_read import load_pddl
        from nowplan.worlds.symbolic import SymbolicWorld

        prob = load_pddl(args.pddl[0], args.pddl[1], args.criticality)
        if args.criticality == "auto" and hierarchical:
            from nowplan.planning.problem_hierarchy import prepare_problem

            prob = prepare_problem(prob)  # reachability statics and goal stages (docs/pddl.md)
        from nowplan.planning.derived_state import derived_closure

        # derived predicates evaluated by rules: recomputed after every action (None without them)
        closure = derived_closure(prob.domain, prob.objects)
        world = SymbolicWorld(prob.domain, prob.init, seed=args.seed, closure=closure)
        return Episode(prob, world, SymbolicBelief(prob.init, closure), f"PDDL {args.pddl[1]}")
    if not args.domain:
        raise UsageError("give --domain NAME (e.g. --domain logistics) or DOMAIN.pddl PROBLEM.pddl")
    spec = get_domain(args.domain)
    return spec.scenario(args.scenario or spec.default_scenario)(args.seed)


def main(args: argparse.Namespace) -> int:
    overrides: dict[str, Any] = {}
    if args.max_actions is not None:
        overrides["max_actions"] = args.max_actions
    if args.time_limit is not None:
        overrides["time_limit"] = args.time_limit
    base = None if args.pddl or not args.domain else get_domain(args.domain).planner
    strategy = parse_strategy(args.strategy, base_planner=base, **overrides)
    if args.max_nodes is not None:
        strategy = replace(strategy, planner=replace(strategy.planner, max_nodes=args.max_nodes))
    if args.criticality == "auto":
        strategy = auto_hierarchy_strategy(strategy, pddl=bool(args.pddl))
    if args.pddl and args.max_nodes is None and strategy.planner.forward_max_nodes is None:
        # the root's forward searches get `nowplan plan`'s node budget, so the time limit ends them as
        # it ends flat planning's (IPC floor-tile, parking, tidybot need more than the regression
        # search's 50,000); refinements keep that one (acting/refine_flat.call_config)
        strategy = replace(strategy, planner=replace(strategy.planner, forward_max_nodes=FORWARD_NODES))
    if args.trace is not None and args.trace.is_dir():
        raise UsageError(f"--trace {args.trace} is a directory; give a file path, e.g. {args.trace / 'trace.jsonl'}")
    episode = build_episode(args, strategy.hierarchical)
    if episode.problem.domain.axioms:
        strategy = axiom_strategy(episode.problem.domain, strategy)
    if args.pddl and args.max_actions is None:
        strategy = replace(strategy, max_actions=pddl_action_budget(episode.problem.objects, strategy.max_actions))
    if args.failure_prob is not None or args.exogenous_prob is not None:
        from nowplan.worlds.base import FaultInjection

        if not isinstance(episode.world, FaultInjection):
            raise UsageError("--failure-prob/--exogenous-prob: this domain's world takes no faults "
                             "(it is not a nowplan SimulatedWorld and has no set_faults); drop them")
        try:
            episode.world.set_faults(failure_prob=args.failure_prob, exogenous_prob=args.exogenous_prob)
        except ValueError as exc:
            raise UsageError(f"--failure-prob/--exogenous-prob: {exc}") from exc
    render = None
    if args.frames:
        if not args.trace:
            raise UsageError("--frames needs --trace FILE (frames are stored in the trace)")
        if args.pddl or get_domain(args.domain).renderer is None:
            raise UsageError("--frames: this problem's domain has no renderer; drop --frames")
        render = get_domain(args.domain).renderer
    if not args.json:  # say what runs before it runs (a run may take a while)
        where = f"domain {args.domain}, scenario {args.scenario or get_domain(args.domain).default_scenario}" \
            if not args.pddl else f"domain file {args.pddl[0]}"
        faults = "".join(f", {name} p={p:g}" for name, p in (("failure", args.failure_prob),
                                                             ("exogenous", args.exogenous_prob)) if p is not None)
        print(f"nowplan run: {episode.description}{faults} ({where}); strategy {strategy.name}, seed {args.seed}",
              flush=True)
        goal = str(episode.problem.goal)
        print(f"goal: {goal if len(goal) <= 300 else goal[:297] + '...'}\n", flush=True)
    with Trace(args.trace) as trace:
        metrics = run_episode(episode, strategy, seed=args.seed, trace=trace, render=render, every=args.frames or 1)
    if args.json:
        print(json.dumps(metrics.to_dict(), indent=2))
    else:
        if args.tree:
            print(render_text(trace.events))
            print()
        print(metrics.summary())
        if "node_limit" in metrics.reason:
            print("hint: a planner call ran out of node expansions; raise them with --max-nodes N")
        if args.trace:
            print(f"trace: {args.trace}")
    return 0 if metrics.outcome.value == "reached" else 1


def auto_hierarchy_strategy(strategy: Strategy, pddl: bool = True) -> Strategy:
    """The settings ``nowplan run --criticality auto`` adds to ``strategy`` (``benchmarks/criticality_auto.py``
    runs with the same): refine-flat, forward search at every level, hidden costs and regrouping."""
    if strategy.hierarchical and not strategy.refine_flat:
        # an automatic hierarchy is ordered-monotonic, not downward refinable: fall back on failure
        strategy = replace(strategy, refine_flat=True, switches=(*strategy.switches, "refine-flat"),
                           name=f"{strategy.name}+refine-flat")
    if pddl and strategy.planner.engine == "auto":
        # forward search at every level, as the automatic hierarchy was measured with
        # (benchmarks/criticality_auto.py): the default regression at abstract levels spent whole
        # budgets on real IPC files' top-level plans (elevators p01: 60 s, forward 0.03 s)
        strategy = replace(strategy, planner=replace(strategy.planner, engine="forward"))
    if pddl:
        # abstract actions cost an estimate of their hidden preconditions (planning/hidden_costs.py):
        # with their own costs only, IPC transport's top level handed packages to trucks wherever they
        # were and refinements swapped in sibling drops, 115 actions and cost 6,822 on p01 (flat: 1,146)
        strategy = replace(strategy, planner=replace(strategy.planner, hidden_costs=True))
    if strategy.hierarchical and not strategy.planner.regroup and "noregroup" not in strategy.switches:
        # every order of an abstract plan's independent steps costs the same at its level, not below it:
        # the steps are regrouped by what their level hides (planning/regroup.py; gripper-250: 997
        # actions, one ball a trip, before)
        strategy = replace(strategy, planner=replace(strategy.planner, regroup=True),
                           switches=(*strategy.switches, "regroup"), name=f"{strategy.name}+regroup")
    return strategy
