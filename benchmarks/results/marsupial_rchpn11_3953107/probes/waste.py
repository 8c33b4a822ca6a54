import sys, time
from collections import defaultdict
from nowplan.acting import arrange as am, reorder as rm
from nowplan.domains.marsupial import loader as lp, model as mm
from nowplan.domains.marsupial.flatcmp import timed_run
from nowplan.domains.marsupial.scenarios import episode
cur = []; tot = defaultdict(lambda: [0, 0.0])
orig_stow = lp.can_stow_in_turn
def stow(*a, **k):
    t0 = time.process_time(); r = orig_stow(*a, **k); dt = time.process_time() - t0
    if cur: cur[-1].append((dt, r))
    return r
lp.can_stow_in_turn = stow
orig_arr = rm.arrange
def arr(s1, s2, belief, **kw):
    cur.append([])
    try:
        v = orig_arr(s1, s2, belief, **kw); return v
    finally:
        rec = cur.pop()
        for dt, r in rec:
            k = (str(kw.get("want")), str(v), "stow=" + str(r))
            t = tot[k]; t[0] += 1; t[1] += dt
rm.arrange = arr
for trial in range(2):
    for n in range(5, 11):
        timed_run(episode("both", n, trial), "hpn+peephole", trial, 600.0)
for k, v in sorted(tot.items()): print(k, v[0], "%.3f" % v[1])
