"""RCHPN against HPN per regime group for seed 002 runs of two trees (main, then a branch).

    python compare.py runs_main.jsonl runs_branch.jsonl [more pairs ...]

Per group: RCHPN/HPN CPU of the whole runs (ratio of sums), the sums themselves and RCHPN's
extra CPU (RCHPN - HPN), the mean of per-problem increases (issue 17's figure), the ratio of
the planner's calls alone (planning_cpu_s), the cost decrease, and whether both trees ended
every run at the same cost after the same number of actions.
"""

import json
import statistics
import sys

GROUP = {"single": "single", "origins": "one side", "dests": "one side", "both": "both"}


def load(path):
    return {(r["regime"], r["packages"], r["trial"], r["strategy"]): r for r in map(json.loads, open(path))}


def table(runs):
    out = {}
    for g in ("single", "one side", "both"):
        keys = sorted({k[:3] for k in runs if GROUP[k[0]] == g})
        ok = [k for k in keys if runs[k + ("hpn",)]["goal_holds"] and runs[k + ("hpn+peephole",)]["goal_holds"]]
        h = sum(runs[k + ("hpn",)]["cpu_s"] for k in ok)
        p = sum(runs[k + ("hpn+peephole",)]["cpu_s"] for k in ok)
        hp = sum(runs[k + ("hpn",)]["planning_cpu_s"] for k in ok)
        pp = sum(runs[k + ("hpn+peephole",)]["planning_cpu_s"] for k in ok)
        inc = statistics.mean(100 * (runs[k + ("hpn+peephole",)]["cpu_s"] / runs[k + ("hpn",)]["cpu_s"] - 1) for k in ok)
        dec = statistics.mean(100 * (1 - runs[k + ("hpn+peephole",)]["cost"] / runs[k + ("hpn",)]["cost"]) for k in ok)
        out[g] = (len(ok), p / h, h, p, p - h, inc, pp / hp, dec)
    return out


def main(paths):
    print("| runs | group | problems | RCHPN/HPN CPU | HPN s | RCHPN s | extra s | mean per-problem increase % "
          "| planner calls RCHPN/HPN | cost decrease % |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for path in paths:
        for g, (n, ratio, h, p, extra, inc, plan, dec) in table(load(path)).items():
            print(f"| {path} | {g} | {n} | {ratio:.2f} | {h:.1f} | {p:.1f} | {extra:.1f} | {inc:.0f} | {plan:.2f} | {dec:.2f} |")
    for a, b in zip(paths[::2], paths[1::2]):
        ra, rb = load(a), load(b)
        same = sum(1 for k in ra if k in rb and (ra[k]["cost"], ra[k]["actions"]) == (rb[k]["cost"], rb[k]["actions"]))
        print(f"\n{a} / {b}: {same} of {len(ra)} runs end at the same cost after the same number of actions")


if __name__ == "__main__":
    main(sys.argv[1:])
