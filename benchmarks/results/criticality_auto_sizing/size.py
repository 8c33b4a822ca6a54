import sys, json, tempfile
from pathlib import Path
sys.path[:0] = ["/work/wt-auto7", "/work/wt-auto7/src"]
from benchmarks.classical.generate import generate, domain_file
from benchmarks.criticality_auto import run_one
# usage: size.py domain seed k=v,k=v ...  (each a candidate); flat only
dom, seed = sys.argv[1], int(sys.argv[2])
for spec in sys.argv[3:]:
    params = {k: int(v) for k, v in (x.split("=") for x in spec.split(","))}
    with tempfile.TemporaryDirectory() as t:
        p = Path(t) / "p.pddl"; p.write_text(generate(dom, params, seed))
        r = run_one(domain_file(dom), p, None, "flat", 60.0, "forward")
    print(dom, spec, r["outcome"], "total", r["total_cpu_s"], "plan", r["planning_cpu_s"], "cost", r["cost"], "acts", r["actions"], r["reason"][:200], flush=True)
