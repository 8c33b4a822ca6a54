import sys, time
from nowplan.core import domain as dm
from nowplan.acting import peephole as peephole_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
inside = [0]; calls = [0]; seen = set(); tt=[0.0]
orig_holds = dm.Domain.holds
def holds(self, a, belief):
    if inside[0]:
        calls[0] += 1; seen.add((id(getattr(belief, "state", belief)), a))
        t=time.perf_counter(); r = orig_holds(self, a, belief); tt[0]+=time.perf_counter()-t; return r
    return orig_holds(self, a, belief)
dm.Domain.holds = holds
for name in ("_next_step", "applicable"):
    f = getattr(peephole_mod.Peephole, name)
    def w(self, ex, frame, f=f):
        inside[0] += 1
        try: return f(self, ex, frame)
        finally: inside[0] -= 1
    setattr(peephole_mod.Peephole, name, w)
for trial in range(2):
    for n in (6, 8, 10):
        seen.clear()
        timed_run(episode("both", n, trial), "hpn+peephole", trial, 600.0)
        print(n, trial, calls[0], len(seen), "%.3f"%tt[0]); calls[0]=0; tt[0]=0
