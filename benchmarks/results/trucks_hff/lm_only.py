import sys, heapq, itertools, math
import nowplan.planning.forward as fw
from nowplan.planning.landmarks import LandmarkCount
from nowplan.planning.hff import RelaxedHeuristic
cap = {}
orig = fw.search
def spy(task, **kw):
    cap['task'] = task; kw['max_nodes'] = 1
    return orig(task, **kw)
fw.search = spy
from nowplan.cli import main
try: main(["plan", sys.argv[1], sys.argv[2], "--improve", "0", "--max-nodes", "1"])
except SystemExit: pass
task = cap['task']
ff = RelaxedHeuristic(task, "ff", "one")
lm = LandmarkCount(task, native=ff.native)
succ = fw._Successors(task)
name = lambda a: str(task.actions[a]) if hasattr(task, 'actions') else a
def lmonly(use_ff_dead=True, limit=200000):
    init = task.init
    acc = {init: lm.initial_accepted()}
    parent = {init: None}
    h0, _ = lm.evaluate(init, acc[init])
    q = []; t = itertools.count(); exp = 0
    for a in succ(init): heapq.heappush(q, (h0, next(t), init, a))
    while q:
        _, _, ps, a = heapq.heappop(q)
        s = fw._apply(task, ps, a)
        if s in parent: continue
        parent[s] = (ps, a); acc[s] = lm.accept(acc[ps], s); exp += 1
        if fw._goal_reached(task, s): return exp, len(fw._path(task, parent, s))
        if exp > limit: return exp, None
        if use_ff_dead and ff.evaluate(s)[0] == math.inf: continue
        h, _ = lm.evaluate(s, acc[s])
        for b in succ(s): heapq.heappush(q, (h, next(t), s, b))
    return exp, None
print("lm-only lazy gbfs (h_FF only for dead ends):", lmonly(True))
def drop(pred):
    keep = [i for i, d in enumerate(lm.sets) if not any(str(task.facts[f]).startswith(pred) for f in d)]
    idx = {o: n for n, o in enumerate(keep)}
    lm.sets = [lm.sets[i] for i in keep]
    lm.before = {idx[i]: [idx[j] for j in v if j in idx] for i, v in lm.before.items() if i in idx}
    lm.reasonable = {idx[i]: [idx[j] for j in v if j in idx] for i, v in lm.reasonable.items() if i in idx}
    lm.is_goal = [len(d) == 1 and next(iter(d)) in lm.goal for d in lm.sets]
    lm.of_fact = {}
    for i, d in enumerate(lm.sets):
        for f in sorted(d): lm.of_fact.setdefault(f, []).append(i)
import copy
saved = (lm.sets, lm.before, lm.reasonable, lm.is_goal, lm.of_fact)
for p in ["free", "time-now", "free(a1"]:
    lm.sets, lm.before, lm.reasonable, lm.is_goal, lm.of_fact = saved
    drop(p); print("drop", p, lmonly(True))
lm.sets, lm.before, lm.reasonable, lm.is_goal, lm.of_fact = saved
lm.reasonable = {}; print("no reasonable", lmonly(True))
lm.sets, lm.before, lm.reasonable, lm.is_goal, lm.of_fact = saved
lm.before = {}; print("no necessary", lmonly(True))
