"""The kitchen's first planning call (as the online policy makes it), with node counts."""
import sys, time, random, logging, collections
from nowplan.domains.kitchen.tasks import make
from nowplan.planning.config import PlannerConfig
from nowplan.planning.context import PlanningContext
from nowplan.planning.regression import plan
from nowplan.core.levels import flat_levels
task = sys.argv[1] if len(sys.argv) > 1 else "cook"
seeds = [int(s) for s in (sys.argv[2] if len(sys.argv) > 2 else "0").split(",")]
for seed in seeds:
    ep = make(task, seed % 25, seed // 25)
    p = ep.problem
    b = ep.belief
    ctx = PlanningContext((), {"online": True, "heuristic": b.planning_heuristic, "whole_problem": True})
    t = time.process_time()
    r = plan(p.domain, p.objects, b, p.goal, flat_levels(), PlannerConfig(time_limit=300), ctx, random.Random(0))
    print(task, seed, r.status.value, "expanded", r.expanded, "generated", r.generated, "cpu %.1f" % (time.process_time() - t), r.attempts, r.reason[:80])
    if r.plan:
        for s in r.plan.steps: print("   ", s.action.pddl() if s.action else None)
