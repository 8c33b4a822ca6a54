"""CPU seconds of `nowplan plan DOMAIN PROBLEM --json` run in-process (imports done once) per classical instance."""
import sys, glob, time, contextlib, os, json, io
from nowplan.cli import main
files = sorted(glob.glob('benchmarks/classical/*/p0*.pddl'))
out = {}
for rep in range(int(sys.argv[2])):
    for p in files:
        d = p.rsplit('/', 1)[0] + '/domain.pddl'
        buf = io.StringIO()
        t = time.process_time()
        with contextlib.redirect_stdout(buf):
            try:
                main(['plan', d, p, '--json'])
            except SystemExit:
                pass
        out.setdefault(p, []).append(time.process_time() - t)
json.dump(out, open(sys.argv[1], 'w'))
