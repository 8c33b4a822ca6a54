"""Summarise cpu.py's JSON files: CPU seconds per instance, the smaller of the runs, branch against main."""
import json, math, sys
A = [json.load(open(f)) for f in sys.argv[1].split(",")]
M = [json.load(open(f)) for f in sys.argv[2].split(",")]
keys = sorted(A[0])
a = {k: min(x[k][0] for x in A) for k in keys}
m = {k: min(x[k][0] for x in M) for k in keys}
print(f"sum CPU (min over runs): branch {sum(a.values()):.2f} s, main {sum(m.values()):.2f} s;"
      f" geometric mean per instance branch/main {math.exp(sum(math.log(a[k] / m[k]) for k in keys) / len(keys)):.3f}")
for i, (x, y) in enumerate(zip(A, M)):
    print(f"run {i + 1}: branch {sum(v[0] for v in x.values()):.2f} s, main {sum(v[0] for v in y.values()):.2f} s")
for d in sorted({k.split('/')[2] for k in keys}):
    ks = [k for k in keys if k.split('/')[2] == d]
    print(f"  {d:12s} {sum(a[k] for k in ks):.3f} vs {sum(m[k] for k in ks):.3f} s")
