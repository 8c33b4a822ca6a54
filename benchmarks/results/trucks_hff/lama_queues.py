"""nowplan's Python lama loop (kernel h_FF), counting pops per queue, dead ends per queue and progress boosts."""
import inspect, math, sys
import nowplan.planning.lama as lama
import nowplan.planning.forward as fw
from nowplan.planning.hff import RelaxedHeuristic
class FastPyLoop(RelaxedHeuristic):
    def __init__(self, *a, **k):
        super().__init__(*a, **k); self._k = self.native; self.native = None
    def evaluate(self, s):
        self.evaluations += 1; return self._k.evaluate(s)
src = inspect.getsource(lama.lama_search)
src = src.replace("        _, _, parent_state, a = heapq.heappop(queues[k])",
                  "        _, _, parent_state, a = heapq.heappop(queues[k]); STATS['pops'][k] += 1")
src = src.replace("        hf, pf = ff.evaluate(state)\n        if hf == math.inf:\n            continue",
                  "        hf, pf = ff.evaluate(state)\n        if hf == math.inf:\n            STATS['dead'][k] += 1\n            continue\n        STATS['live'][k] += 1")
src = src.replace("        if progress:\n", "        if progress:\n            STATS['boosts'] += 1\n")
src = src.replace("        k = min((i for i in range(4) if queues[i]), key=lambda i: priority[i])",
                  "        k = min((i for i in range(4) if queues[i]), key=lambda i: priority[i])\n"
                  "        STATS['selections_with_preferred_empty'] += not queues[1] and not queues[3]")
assert src.count("STATS") == 5, src.count("STATS")
ns = dict(vars(lama)); ns["RelaxedHeuristic"] = FastPyLoop
STATS = {"pops": [0] * 4, "dead": [0] * 4, "live": [0] * 4, "boosts": 0, "selections_with_preferred_empty": 0}; ns["STATS"] = STATS
exec(src, ns)
cap = {}
o = fw.search
def spy(task, **kw):
    cap['task'] = task; kw['max_nodes'] = 1
    return o(task, **kw)
fw.search = spy
from nowplan.cli import main
try: main(["plan", sys.argv[1], sys.argv[2], "--improve", "0", "--max-nodes", "1"])
except SystemExit: pass
r = ns["lama_search"](cap['task'], cost_type="plusone", max_nodes=300000)
print(r.status.name, "expanded", r.expanded)
print("queues: ff, ff preferred, lm, lm preferred")
for k, v in STATS.items(): print(k, v)
