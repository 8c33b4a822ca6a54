"""Cost decrease and RCHPN/HPN CPU (ratio of sums) per regime group, before against after.

    python compare.py runs_before.jsonl runs_after.jsonl
"""
import json, sys
from collections import defaultdict
def load(p):
    d = {}
    for l in open(p):
        r = json.loads(l); d[(r["regime"], r["packages"], r["trial"], r["strategy"])] = r
    return d
b = load(sys.argv[1]); a = load(sys.argv[2])
grp = {"single": "single", "origins": "one side", "dests": "one side", "both": "both"}
for name in ("single", "one side", "both"):
    for tag, d in (("before", b), ("after", a)):
        keys = [k for k in d if grp[k[0]] == name and k[3] == "hpn"]
        decs = []; hc = rc = 0
        for k in keys:
            h = d[k]; r = d[(k[0], k[1], k[2], "hpn+peephole")]
            if h["goal_holds"] and r["goal_holds"]:
                decs.append(100 * (1 - r["cost"] / h["cost"])); hc += h["cpu_s"]; rc += r["cpu_s"]
        print(f"{name:9s} {tag:6s} n={len(decs)} dec {sum(decs)/len(decs):.2f}%  RCHPN/HPN CPU (ratio of sums) {rc/hc:.2f}")
    ch = [(k, b[(k[0],k[1],k[2],'hpn+peephole')]['cost'], a[(k[0],k[1],k[2],'hpn+peephole')]['cost']) for k in b if grp[k[0]]==name and k[3]=='hpn' and b[(k[0],k[1],k[2],'hpn+peephole')]['cost'] != a[(k[0],k[1],k[2],'hpn+peephole')]['cost']]
    print("   changed:", ", ".join(f"{k[0]}-{k[1]} t{k[2]} {x:g}->{y:g}" for k, x, y in ch))
