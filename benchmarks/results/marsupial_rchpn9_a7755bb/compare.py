"""Compare two seed-002 full runs (JSON lines of `nowplan reproduce 002 --full --runs FILE`): per regime RCHPN/HPN CPU
(ratio of sums), solved, mean cost decrease and CPU increase, and the RCHPN runs whose cost, length or outcome differ.

    python compare.py runs1_main_a56ea44.jsonl runs1_a7755bb.jsonl
"""
import json, sys, statistics
from collections import defaultdict
def load(p):
    d = {}
    for line in open(p):
        r = json.loads(line); d[(r["regime"], r["packages"], r["trial"], r["strategy"])] = r
    return d
a, b = load(sys.argv[1]), load(sys.argv[2])
keys = sorted(set(a) & set(b))
print("runs in both:", len(keys), "of", len(a), len(b))
for reg in ("single", "origins", "dests", "both", "one side"):
    regs = ("origins", "dests") if reg == "one side" else (reg,)
    out = []
    for d, name in ((a, "A"), (b, "B")):
        ks = [k for k in keys if k[0] in regs]
        cpu = {s: sum(d[k]["cpu_s"] for k in ks if k[3] == s) for s in ("hpn", "hpn+peephole")}
        solved = sum(1 for k in ks if k[3] == "hpn+peephole" and d[k]["outcome"] == "reached")
        probs = sorted({k[:3] for k in ks})
        dec = [100 * (1 - d[p + ("hpn+peephole",)]["cost"] / d[p + ("hpn",)]["cost"]) for p in probs if (p + ("hpn",)) in d and (p+("hpn+peephole",)) in d]
        inc = [100 * (d[p + ("hpn+peephole",)]["cpu_s"] / d[p + ("hpn",)]["cpu_s"] - 1) for p in probs if (p + ("hpn",)) in d and (p+("hpn+peephole",)) in d]
        rc = sum(d[p + ("hpn+peephole",)]["cost"] for p in probs if (p+("hpn+peephole",)) in d)
        out.append(f"{name}: RCHPN/HPN {cpu['hpn+peephole']/max(cpu['hpn'],1e-9):.3f} (HPN {cpu['hpn']:.1f} RCHPN {cpu['hpn+peephole']:.1f}) solved {solved}/{len(probs)} dec {statistics.mean(dec):.2f}% inc {statistics.mean(inc):.0f}% RCHPN cost sum {rc:g}")
    diff = [k for k in keys if k[0] in regs and k[3] == "hpn+peephole" and (a[k]["cost"], a[k]["actions"], a[k]["outcome"]) != (b[k]["cost"], b[k]["actions"], b[k]["outcome"])]
    print(f"{reg}: " + " | ".join(out) + f" | RCHPN runs differing: {len(diff)}")
    for k in diff:
        print("   ", k, a[k]["cost"], "->", b[k]["cost"], a[k]["outcome"], "->", b[k]["outcome"], f"cpu {a[k]['cpu_s']:.2f} -> {b[k]['cpu_s']:.2f}")
hd = [k for k in keys if k[3] == "hpn" and (a[k]["cost"], a[k]["actions"]) != (b[k]["cost"], b[k]["actions"])]
print("HPN runs differing:", len(hd))
