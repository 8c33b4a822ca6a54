import sys, time, json, hashlib
from nowplan.acting import peephole as pm
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
mode = sys.argv[1]
orig = pm.Peephole._next_step
def ns(self, ex, frame):
    if mode == "nobelow" and frame.info.get("under_joint") is not None:
        cap = self._cap; self._cap = 1
        try: return orig(self, ex, frame)
        finally: self._cap = cap
    return orig(self, ex, frame)
pm.Peephole._next_step = ns
regs = sys.argv[2].split(",")
for trial in range(int(sys.argv[3]), int(sys.argv[4])):
    for n in range(5, 11):
        for reg in regs:
            out = {}
            for s in ("hpn", "hpn+peephole"):
                m, cpu, ok = timed_run(episode(reg, n, trial), s, trial, 600.0)
                out[s] = (cpu, m.execution_cost)
            print(json.dumps({"reg": reg, "n": n, "t": trial, "hpn": out["hpn"], "rc": out["hpn+peephole"]}), flush=True)
