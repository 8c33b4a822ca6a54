import sys, cProfile, pstats, io
from nowplan.acting import hpn as hpn_mod
from nowplan.acting import peephole as peephole_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
profs = {k: cProfile.Profile() for k in ("hpn-plain", "rc-below", "rc-joint", "rc-plain")}
orig = hpn_mod.Executive.make_plan
cur = [None]
def make_plan(self, goal, levels, parent, *a, **k):
    info = parent.info
    if info.get("joint") is not None and info.get("joint") == parent.i: kind = "rc-joint"
    elif peephole_mod._combination(parent) is not None: kind = "rc-below"
    else: kind = "rc-plain" if cur[0] != "hpn" else "hpn-plain"
    p = profs[kind]
    p.enable()
    try: return orig(self, goal, levels, parent, *a, **k)
    finally: p.disable()
hpn_mod.Executive.make_plan = make_plan
for trial in range(3):
    for n in (6, 8, 10):
        for strat in ("hpn", "hpn+peephole"):
            cur[0] = strat
            timed_run(episode("both", n, trial), strat, trial, 600.0)
for k, p in profs.items():
    buf = io.StringIO(); st = pstats.Stats(p, stream=buf)
    st.sort_stats("tottime").print_stats(25)
    st.sort_stats("cumulative").print_stats(40)
    open(f"/tmp/b11/calls.{k}", "w").write(buf.getvalue())
