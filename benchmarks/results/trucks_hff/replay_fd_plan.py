"""h_FF and nowplan's landmark count along Fast Downward's plan (argv: domain problem sas_plan)."""
import sys
import nowplan.planning.forward as fw
from nowplan.planning.landmarks import LandmarkCount
from nowplan.planning.hff import RelaxedHeuristic
cap = {}
o = fw.search
def spy(task, **kw):
    cap['task'] = task; kw['max_nodes'] = 1
    return o(task, **kw)
fw.search = spy
from nowplan.cli import main
try: main(["plan", sys.argv[1], sys.argv[2], "--improve", "0", "--max-nodes", "1"])
except SystemExit: pass
task = cap['task']
ff = RelaxedHeuristic(task, "ff", "one")
lm = LandmarkCount(task, native=ff.native)
import re
key: dict = {}
for i, a in enumerate(task.actions):  # ADL variants are named load-v1, load-v2, ...: every one kept
    key.setdefault((re.sub(r"-v\d+$", "", a.name.lower()), tuple(str(x).lower() for x in a.args)), []).append(i)
steps = [l.strip()[1:-1].split() for l in open(sys.argv[3]) if l.startswith("(")]
s = task.init; acc = lm.initial_accepted()
print("step", "action", "h_ff", "h_lm", "n_applicable", "dead_successors")
def row(k, name):
    hf, pref = ff.evaluate(s); hl, _ = lm.evaluate(s, acc)
    succ = list(fw._Successors(task)(s))
    dead = sum(1 for a in succ if ff.evaluate(fw._apply(task, s, a))[0] == float("inf"))
    print(k, name, hf, hl, len(succ), dead, "pref" if False else "")
row(0, "init")
for k, st in enumerate(steps, 1):
    a = next(i for i in key[(st[0], tuple(st[1:]))] if all(p in s for p in task.pre[i]))
    s = fw._apply(task, s, a); acc = lm.accept(acc, s)
    row(k, " ".join(st))
