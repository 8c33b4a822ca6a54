import sys, math
import nowplan.planning.hff as hff
import nowplan.planning.lama as lama
hff.kernel_class = lambda: None
cnt = {"eval": 0, "dead": 0}
orig = hff.RelaxedHeuristic.evaluate
def ev(self, s):
    r = orig(self, s); cnt["eval"] += 1
    if r[0] == math.inf: cnt["dead"] += 1
    return r
hff.RelaxedHeuristic.evaluate = ev
import nowplan.planning.forward as fw
o = fw.search
def spy(task, **kw):
    r = o(task, **kw)
    print(kw.get("method"), r.status.name, "expanded", r.expanded, "generated", r.generated, cnt, file=sys.stderr, flush=True)
    cnt["eval"] = cnt["dead"] = 0
    return r
fw.search = spy
from nowplan.cli import main
for m in sys.argv[3:]:
    try: main(["plan", sys.argv[1], sys.argv[2], "--improve", "0", "--search", m])
    except SystemExit: pass
