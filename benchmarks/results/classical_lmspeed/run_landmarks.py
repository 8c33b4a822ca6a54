"""CPU of one `nowplan run` on a PDDL problem and the share of LandmarkCount.__init__ in it (argv: the run arguments)."""
import sys, time, contextlib, io
from nowplan.cli import main
from nowplan.planning import landmarks as L
acc = {'n': 0, 't': 0.0}
f = L.LandmarkCount.__init__
def w(self, *a, **k):
    t = time.process_time(); f(self, *a, **k); acc['t'] += time.process_time() - t; acc['n'] += 1
L.LandmarkCount.__init__ = w
t = time.process_time()
with contextlib.redirect_stdout(io.StringIO()):
    try:
        main(['run', *sys.argv[1:], '--json'])
    except SystemExit:
        pass
tot = time.process_time() - t
print(f"run CPU {tot:.2f} s; LandmarkCount built {acc['n']} times, {acc['t']:.3f} s CPU ({100 * acc['t'] / tot:.1f} %)")
