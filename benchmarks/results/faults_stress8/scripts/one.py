import sys, time, logging, cProfile, pstats
from dataclasses import replace
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.registry import get_domain
from nowplan.experiments.faults import apply_faults, split_scenario
from nowplan.trace import Trace
dom, scen, st, seed, tl = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]), float(sys.argv[5])
cpu = "--cpu" in sys.argv
base, f = split_scenario(scen)
spec = get_domain(dom)
ep = spec.scenario(base)(seed); apply_faults(ep, f)
strategy = parse_strategy(st, base_planner=spec.planner, time_limit=tl)
if cpu:
    strategy = replace(strategy, planner=replace(strategy.planner, clock="cpu"))
t = time.time(); c = time.process_time()
tr = Trace(sys.argv[6]) if len(sys.argv) > 6 and not sys.argv[6].startswith("--") else None
m = run_episode(ep, strategy, seed, trace=tr)
print(m.outcome.value, m.actions, m.plans_made, m.plan_failures, "wall", round(time.time()-t,1), "cpu", round(time.process_time()-c, 1), m.reason[:300])
