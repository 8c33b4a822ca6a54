"""Count planner calls repeating an earlier one exactly (belief, goal, levels, config, rng state)."""
import sys, time, hashlib, pickle
from collections import defaultdict
from nowplan.acting import hpn as hpn_mod
from nowplan.acting import peephole as peephole_mod
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode

log = []
orig = hpn_mod.Executive.make_plan
def make_plan(self, goal, levels, parent, *a, **k):
    info = parent.info
    if info.get("joint") is not None and info.get("joint") == parent.i: kind = "joint"
    elif peephole_mod._combination(parent) is not None: kind = "below"
    else: kind = "plain"
    rs = hashlib.sha1(pickle.dumps(self.rng.getstate())).hexdigest()[:10] if hasattr(self.rng, "getstate") else "?"
    key_ng = (hash(self.belief), str(sorted(map(str, goal))), repr(levels), kind)
    key = key_ng + (rs,)
    t0 = time.process_time()
    res = orig(self, goal, levels, parent, *a, **k)
    dt = time.process_time() - t0
    log.append((key, key_ng, dt, kind, res is not None))
    return res
hpn_mod.Executive.make_plan = make_plan
tot = defaultdict(lambda: [0, 0.0, 0, 0.0, 0, 0.0])
for trial in range(int(sys.argv[2])):
    for n in map(int, sys.argv[1].split(",")):
        for strat in ("hpn", "hpn+peephole"):
            log.clear()
            ep = episode("both", n, trial)
            m, cpu, ok = timed_run(ep, strat, trial, 600.0)
            seen, seen_ng = set(), set()
            for key, kng, dt, kind, solved in log:
                t = tot[(strat, kind)]
                t[0] += 1; t[1] += dt
                if key in seen: t[2] += 1; t[3] += dt
                if kng in seen_ng: t[4] += 1; t[5] += dt
                seen.add(key); seen_ng.add(kng)
            print(strat, n, trial, f"{cpu:.2f}", file=sys.stderr)
for k, v in sorted(tot.items()):
    print(k, "calls %d %.2fs | exact repeats %d %.2fs | repeats ignoring rng %d %.2fs" % tuple(v))
