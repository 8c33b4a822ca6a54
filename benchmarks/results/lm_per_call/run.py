"""One auto-HPN (or flat) run of a generated classical instance with a given checkout's nowplan.

    python run.py CHECKOUT DOMAIN run|prof auto|flat

Prints the run's outcome, planning CPU, cost, actions, plans made and hashes of
the executed actions and of the plans made (goal, cost, steps), so two checkouts
can be compared for the same plans; ``prof`` adds a cProfile listing.
"""
import sys, cProfile, pstats, tempfile, time, hashlib, json
from pathlib import Path
from dataclasses import replace
sys.path.insert(0, sys.argv[1]); sys.path.insert(0, sys.argv[1] + "/src")
from benchmarks.classical.generate import generate, domain_file
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.belief.symbolic import SymbolicBelief
from nowplan.domains.registry import Episode
from nowplan.io.pddl_read import load_pddl
from nowplan.planning.abstraction import prepare_problem
from nowplan.worlds.symbolic import SymbolicWorld
from nowplan.trace import Trace
CASES = {"logistics": ({"cities": 6, "places": 4, "airplanes": 3, "packages": 40}, 7),
         "zenotravel": ({"aircraft": 5, "persons": 25, "cities": 10}, 7),
         "driverlog": ({"drivers": 4, "trucks": 4, "packages": 16, "locations": 14}, 7)}
dom = sys.argv[2]; mode = sys.argv[3]; setting = sys.argv[4] if len(sys.argv) > 4 else "auto"
params, seed = CASES[dom]
p = Path(tempfile.mkdtemp()) / f"{dom}.pddl"; p.write_text(generate(dom, params, seed))
def go():
    crit, strategy = ("auto", "hpn+refine-flat") if setting == "auto" else (None, "flat")
    prob = load_pddl(domain_file(dom), p, crit)
    if crit == "auto":
        prob = prepare_problem(prob)
    strat = parse_strategy(strategy)
    strat = replace(strat, time_limit=60, planner=replace(strat.planner, engine="forward"))
    ep = Episode(prob, SymbolicWorld(prob.domain, prob.init, seed=0), SymbolicBelief(prob.init), str(p))
    tr = Trace()
    m = run_episode(ep, strat, seed=0, trace=tr)
    acts = [e["action"] for e in tr.of("action")] if hasattr(tr, "of") else [e["action"] for e in tr.events if e["event"] == "action"]
    plans = [json.dumps([e["goal"], e["cost"], e["steps"]], default=str) for e in tr.events if e["event"] == "plan"]
    return {"outcome": m.outcome.value, "planning_cpu_s": round(m.planning_cpu_s, 3), "cost": m.execution_cost,
            "actions": m.actions, "plans_made": m.plans_made,
            "exec_hash": hashlib.sha1("\n".join(acts).encode()).hexdigest()[:10],
            "plans_hash": hashlib.sha1("\n".join(plans).encode()).hexdigest()[:10]}
if mode == "prof":
    pr = cProfile.Profile(); pr.enable()
    r = go()
    pr.disable(); print(r)
    pstats.Stats(pr).sort_stats("cumulative").print_stats(45)
else:
    print(go())
