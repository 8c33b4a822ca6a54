import sys
import nowplan.planning.forward as fw
from nowplan.planning.landmarks import LandmarkCount
from nowplan.planning.hff import RelaxedHeuristic
cap = {}
orig = fw.search
def spy(task, **kw):
    cap['task'] = task
    kw['max_nodes'] = 1
    return orig(task, **kw)
fw.search = spy
from nowplan.cli import main
try:
    main(["plan", sys.argv[1], sys.argv[2], "--improve", "0", "--max-nodes", "1"])
except SystemExit:
    pass
task = cap['task']
print("facts", len(task.facts), "actions", len(task.pre), "goal", len(task.goal), "init", len(task.init))
ff = RelaxedHeuristic(task, "ff", "one")
lm = LandmarkCount(task, native=ff.native)
print("hff init", ff.evaluate(task.init)[0])
print("landmarks", len(lm.sets), "disj", sum(len(d) > 1 for d in lm.sets),
      "nec orders", sum(len(v) for v in lm.before.values()), "reasonable", sum(len(v) for v in lm.reasonable.values()))
acc0 = lm.initial_accepted()
print("hlm init", lm.evaluate(task.init, acc0)[0])
name = lambda f: str(task.facts[f])
for i, d in enumerate(lm.sets):
    print(i, [name(f) for f in sorted(d)], "before->", lm.before.get(i, []), "reas->", lm.reasonable.get(i, []), "init" if d & task.init else "")
