import sys, time
from collections import defaultdict
from nowplan.acting import hpn as hpn_mod
from nowplan.acting import peephole as peephole_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
tot = defaultdict(lambda: [0, 0.0])
orig = hpn_mod.Executive.make_plan
def make_plan(self, goal, levels, parent, *a, **k):
    info = parent.info
    if info.get("joint") is not None and info.get("joint") == parent.i: kind = "joint"
    elif peephole_mod._combination(parent) is not None: kind = "below"
    elif info.get("fallout") is not None and info.get("fallout") == parent.i: kind = "fallout"
    else: kind = "plain"
    t0 = time.process_time()
    res = orig(self, goal, levels, parent, *a, **k)
    dt = time.process_time() - t0
    st = "ok" if res is not None else self._last_status.value
    t = tot[(kind, st)]; t[0] += 1; t[1] += dt
    return res
hpn_mod.Executive.make_plan = make_plan
for trial in range(2):
    for n in range(5, 11):
        timed_run(episode("both", n, trial), "hpn+peephole", trial, 600.0)
for k, v in sorted(tot.items()): print(k, v[0], "%.2f" % v[1])
