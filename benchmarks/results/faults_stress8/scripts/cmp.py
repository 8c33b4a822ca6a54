"""Before/after on the runs present in both CSV exports: reached per domain x level, fixed, new failures."""
import csv, sys
from collections import defaultdict
def load(paths):
    out = {}
    for p in paths.split(","):
        for r in csv.DictReader(open(p, encoding="utf-8")):
            out[(r["domain"], r["faults"], r["strategy"], r["seed"])] = r
    return out
b, a = load(sys.argv[1]), load(sys.argv[2])
common = sorted(set(b) & set(a))
tab = defaultdict(lambda: [0, 0, 0])
fixed, new, still = [], [], []
for k in common:
    rb, ra = b[k]["outcome"] == "reached", a[k]["outcome"] == "reached"
    t = tab[(k[0], k[1])]
    t[0] += 1; t[1] += rb; t[2] += ra
    if ra and not rb: fixed.append(k)
    if rb and not ra: new.append(k)
    if not ra and not rb: still.append(k)
print(f"{len(common)} runs in both (before {len(b)}, after {len(a)})\n")
print("| domain | faults | runs | reached before | reached after |")
print("|---|---|---|---|---|")
for (d, f), (n, x, y) in sorted(tab.items()):
    print(f"| {d} | {f} | {n} | {x} | {y} |")
n = sum(v[0] for v in tab.values()); x = sum(v[1] for v in tab.values()); y = sum(v[2] for v in tab.values())
print(f"| all | | {n} | {x} | {y} |")
def show(title, ks):
    print(f"\n{title} ({len(ks)}):\n")
    for k in ks:
        rb, ra = b[k], a[k]
        print(f"- {k[0]} {k[1]} {k[2]} seed {k[3]}: before {rb['outcome']} ({rb['reason'][:90]}; {float(rb['planning_cpu_s'] or 0):.1f} CPU s, {float(rb['wall_s']):.0f} s wall) -> after {ra['outcome']} ({ra['reason'][:90]}; {float(ra['planning_cpu_s'] or 0):.1f} CPU s, {float(ra['wall_s']):.0f} s wall)")
show("Fixed (reached after, not before)", fixed)
show("New failures (reached before, not after)", new)
show("Not reached either time", still)
