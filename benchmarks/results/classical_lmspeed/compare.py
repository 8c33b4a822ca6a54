"""Per run: geometric mean, worst and within-2x of nowplan/lama-first wall; and over runs, per-instance medians."""
import csv, math, sys, statistics
from collections import defaultdict

def load(d):
    rows = defaultdict(dict)
    for r in csv.DictReader(open(f"{d}/classical.csv")):
        rows[(r['domain'], r['instance'])][r['planner']] = r
    return rows

def ratios(rows):
    out = {}
    for k, v in rows.items():
        a, b = v.get('nowplan'), v.get('fd-lama-first')
        if a and b and a['solved'] == 'True' and b['solved'] == 'True':
            out[k] = (float(a['wall_s']), float(b['wall_s']), float(a['planning_s'] or 'nan'))
    return out

def summary(name, r):
    q = {k: a / b for k, (a, b, _) in r.items()}
    g = math.exp(sum(math.log(x) for x in q.values()) / len(q))
    w = max(q, key=q.get)
    print(f"{name:28s} geo {g:.3f}x  worst {q[w]:.2f}x ({' '.join(w)})  within 2x {sum(x <= 2 for x in q.values())}/{len(q)}"
          f"  sum planning_s {sum(p for _, _, p in r.values()):.2f}")

groups = defaultdict(list)
for d in sys.argv[1:]:
    label = d.rstrip('/').split('/')[-1]
    r = ratios(load(d))
    summary(label, r)
    groups['after' if 'after' in label else 'main'].append(r)
for name, runs in groups.items():
    keys = set.intersection(*(set(r) for r in runs))
    med = {k: (statistics.median(r[k][0] for r in runs), statistics.median(r[k][1] for r in runs),
               statistics.median(r[k][2] for r in runs)) for k in keys}
    summary(f"{name}: median of {len(runs)} runs", med)

# per instance: median over runs of the ratio ours/lama-first (the ratio within one run)
for name, runs in groups.items():
    keys = set.intersection(*(set(r) for r in runs))
    q = {k: statistics.median(r[k][0] / r[k][1] for r in runs) for k in keys}
    g = math.exp(sum(math.log(x) for x in q.values()) / len(q))
    w = max(q, key=q.get)
    print(f"{name}: per-instance median ratio: geo {g:.3f}x worst {q[w]:.2f}x ({' '.join(w)}) within 2x {sum(x <= 2 for x in q.values())}/{len(q)}")
a, m = groups.get('after'), groups.get('main')
if a and m:
    keys = set.intersection(*(set(r) for r in a + m))
    pa = {k: statistics.median(r[k][2] for r in a) for k in keys}
    pm = {k: statistics.median(r[k][2] for r in m) for k in keys}
    g = math.exp(sum(math.log(pa[k] / pm[k]) for k in keys) / len(keys))
    print(f"in-process planning time (nowplan's planning_time_s), median over runs, after/main: geo {g:.3f}x"
          f"; sums {sum(pa.values()):.2f} s vs {sum(pm.values()):.2f} s")
    for dom in sorted({k[0] for k in keys}):
        ks = [k for k in keys if k[0] == dom]
        print(f"   {dom:12s} {sum(pa[k] for k in ks):.3f} vs {sum(pm[k] for k in ks):.3f} s")
