"""Scratch measurement kept with its results (wip-auto7): where prepare_problem's CPU goes (second of two runs, caches cleared).

    PYTHONPATH=src python benchmarks/results/criticality_auto_08e8c74/parts/prep_split.py zenotravel 7 aircraft=5,persons=25,cities=10
"""
import sys, time, gc, tempfile
from pathlib import Path
sys.path[:0] = [str(Path(__file__).resolve().parents[4]), str(Path(__file__).resolve().parents[4] / "src")]
from benchmarks.classical.generate import generate, domain_file
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import abstraction, reach_statics, dead_ends, task_grounding
import functools, collections
T = collections.Counter()
def timed(mod, name):
    f = getattr(mod, name)
    @functools.wraps(f)
    def g(*a, **k):
        t = time.process_time()
        try: return f(*a, **k)
        finally: T[name] += time.process_time() - t
    setattr(mod, name, g)
timed(reach_statics, "add_reachability_statics"); timed(dead_ends, "irreversible_step"); timed(abstraction, "derive_hierarchy"); timed(abstraction, "goal_stages"); timed(task_grounding, "_ground")
dom, seed, spec = sys.argv[1], int(sys.argv[2]), sys.argv[3]
params = {k: int(v) for k, v in (x.split("=") for x in spec.split(","))}
p = Path(tempfile.mkdtemp()) / "prep.pddl"; p.write_text(generate(dom, params, seed))
for i in range(2):
    T.clear(); task_grounding.clear_cache()
    prob = load_pddl(domain_file(dom), p, "auto")
    t = time.process_time(); abstraction.prepare_problem(prob); tot = time.process_time() - t
print(dom, spec, "prep", round(tot, 4), {k: round(v, 4) for k, v in T.items()})
