import sys
import nowplan.planning.forward as fw
from nowplan.planning.landmarks import LandmarkCount
from nowplan.planning.hff import RelaxedHeuristic
from nowplan.planning.forward import BOOST
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
def run(label, mod):
    ff = RelaxedHeuristic(task, "ff", "plusone")
    lm = LandmarkCount(task, native=ff.native)
    mod(lm)
    sets = [sorted(d) for d in lm.sets]
    before = [lm.before.get(i, []) for i in range(len(sets))]
    reasonable = [lm.reasonable.get(i, []) for i in range(len(sets))]
    out = ff.native.lama(task.init, 500000, sets, before, lambda: False, BOOST, lm.unreachable, reasonable)
    r = fw.native_result(task, out, 500000)
    print(label, r.status, r.expanded, len(r.actions or []))
def none(lm): pass
def no_reas(lm): lm.reasonable = {}
def no_reas_init(lm):
    lm.reasonable = {i: v for i, v in lm.reasonable.items() if not (lm.sets[i] & task.init)}
def no_before(lm): lm.before = {}
run("as is", none); run("no reasonable", no_reas); run("no reasonable to init-true", no_reas_init); run("no necessary", no_before)
def drop(pred):
    def mod(lm):
        keep = [i for i, d in enumerate(lm.sets) if not any(str(task.facts[f]).startswith(pred) for f in d)]
        idx = {o: n for n, o in enumerate(keep)}
        lm.sets = [lm.sets[i] for i in keep]
        lm.before = {idx[i]: [idx[j] for j in v if j in idx] for i, v in lm.before.items() if i in idx}
        lm.reasonable = {idx[i]: [idx[j] for j in v if j in idx] for i, v in lm.reasonable.items() if i in idx}
    return mod
run("drop free", drop("free")); run("drop time", drop("time-now")); run("drop at(truck", drop("at(truck"))
