import sys, math
import nowplan.planning.forward as fw
import nowplan.planning.lama as lama
from nowplan.planning.hff import RelaxedHeuristic
class FastPyLoop(RelaxedHeuristic):  # kernel h_FF, Python lama loop (so the successor order can be changed)
    def __init__(self, *a, **k):
        super().__init__(*a, **k); self._k = self.native; self.native = None
    def evaluate(self, s):
        self.evaluations += 1; r = self._k.evaluate(s)
        if r[0] == math.inf: DEAD[0] += 1
        return r
lama.RelaxedHeuristic = FastPyLoop
DEAD = [0]
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
Orig = fw._Successors
names = [str(a) for a in task.actions]
def variant(key):
    class S(Orig):
        def __call__(self, state):
            return sorted(super().__call__(state), key=key)
    return S
for label, key in [("kernel order", None), ("reversed", lambda a: -a)]:
    lama._Successors = Orig if key is None else variant(key)
    DEAD[0] = 0
    r = lama.lama_search(task, cost_type="plusone", max_nodes=300000)
    print(label, r.status.name, "expanded", r.expanded, "len", len(r.actions or []), "dead ends", DEAD[0], "not dead", r.expanded - DEAD[0], "generated", r.generated, flush=True)
