"""RCHPN's CPU in the two trees of a marsupial_ab.py run, over HPN's pooled from both trees.

HPN's code is the same in both trees (its executed actions are compared too), so its CPU time in
either tree measures only the machine; pooling it halves that noise in the RCHPN/HPN ratio.

    python benchmarks/results/marsupial_rcost12/pool.py benchmarks/results/marsupial_rcost12/ab_*.jsonl
"""

from __future__ import annotations

import json
import sys
from collections import defaultdict


def main() -> None:
    for path in sys.argv[1:]:
        rows = [json.loads(x) for x in open(path) if x.strip()]
        cpu: dict[tuple[str, str], float] = defaultdict(float)
        acts: dict[tuple[str, int], dict[str, str]] = defaultdict(dict)
        for r in rows:
            cpu[(r["tag"], r["strategy"])] += r["cpu"]
            if r["strategy"] == "hpn":
                acts[(r["problem"], r["trial"])][r["tag"]] = r["actions"]
        hpn = (cpu[("before", "hpn")] + cpu[("after", "hpn")]) / 2
        same = sum(1 for v in acts.values() if v.get("before") == v.get("after"))
        b, a = cpu[("before", "hpn+peephole")], cpu[("after", "hpn+peephole")]
        print(f"{path}: RCHPN CPU before {b:.2f} s, after {a:.2f} s (x{a / b:.3f}); HPN {cpu[('before', 'hpn')]:.2f} / "
              f"{cpu[('after', 'hpn')]:.2f} s; RCHPN / pooled HPN {b / hpn:.3f} -> {a / hpn:.3f}; "
              f"HPN same actions in {same} of {len(acts)}")


if __name__ == "__main__":
    main()
