import sys, time
from collections import defaultdict
from nowplan.acting import peephole as peephole_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
tot = defaultdict(lambda: [0, 0.0])
orig = peephole_mod.Peephole._next_step
def ns(self, ex, frame):
    under = "under" if frame.info.get("under_joint") is not None else "top"
    ev = len(ex.trace.events); t0 = time.process_time()
    r = orig(self, ex, frame)
    dt = time.process_time() - t0
    moved = len(ex.trace.events) > ev
    comb = frame.info.get("joint") is not None
    k = (under, "moved" if moved else "none", "comb" if comb else "-", f"depth{len(ex.stack)}")
    t = tot[k]; t[0] += 1; t[1] += dt
    return r
peephole_mod.Peephole._next_step = ns
for trial in range(2):
    for n in range(5, 11):
        timed_run(episode("both", n, trial), "hpn+peephole", trial, 600.0)
for k, v in sorted(tot.items()): print(k, v[0], "%.3f" % v[1])
