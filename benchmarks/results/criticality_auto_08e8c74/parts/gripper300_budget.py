"""Scratch measurement kept with its results (wip-auto7): auto-HPN on gripper with 300 balls, the benchmark's auto setting with a 2000-action budget.

    PYTHONPATH=src python benchmarks/results/criticality_auto_08e8c74/parts/gripper300_budget.py
"""
import sys
import tempfile
from pathlib import Path
sys.path[:0] = [str(Path(__file__).resolve().parents[4]), str(Path(__file__).resolve().parents[4] / "src")]
from dataclasses import replace
from benchmarks.classical.generate import generate, domain_file
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.domains.registry import Episode
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.abstraction import prepare_problem
from nowplan.worlds.symbolic import SymbolicWorld
p = Path(tempfile.mkdtemp()) / "g300.pddl"; p.write_text(generate("gripper", {"balls": 300}, 0))
prob = prepare_problem(load_pddl(domain_file("gripper"), p, "auto"))
s = parse_strategy("hpn+refine-flat")
s = replace(s, time_limit=60, max_actions=2000, planner=replace(s.planner, engine="forward"))
m = run_episode(Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), "g300"), s, seed=0)
print(m.outcome, m.actions, m.execution_cost, m.plans_made)
