"""RCHPN on PDDL with derived resources: auto-HPN against auto-RCHPN and flat planning.

``--strategy hpn+peephole`` on a domain that declares no resources (every PDDL file) uses resources
derived from its operators (``nowplan.acting.derived_resources``, docs/peephole.md).  This runs
``benchmarks/auto_ipc.py``'s runners (each run a ``nowplan`` process with ``--criticality auto``;
flat ``nowplan plan --improve 0``; every solved plan and every run's executed actions validated)
over the classical domains' checked-in instances (``benchmarks/classical/*/p01-p05``) and, with
``--larger``, the larger generated instances of ``benchmarks/criticality_auto.py``'s ``LARGER`` tier,
then writes ``runs.jsonl``, ``auto_ipc.md`` (per pair) and ``auto_rchpn.md`` (per domain: costs
summed over the pairs all three settings solve, the cost decrease of RCHPN over HPN, how many pairs
got cheaper / the same / dearer, and the process CPU ratio RCHPN / HPN).

    PYTHONPATH=src .venv/bin/python benchmarks/auto_rchpn.py --larger --out benchmarks/results/auto_rchpn
    PYTHONPATH=src .venv/bin/python benchmarks/auto_rchpn.py --summarize benchmarks/results/auto_rchpn
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import tempfile
from collections import defaultdict
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
for _p in (ROOT, ROOT / "src"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

from benchmarks import auto_ipc  # noqa: E402
from benchmarks.classical.generate import DOMAINS, domain_file, generate, instance_files  # noqa: E402
from benchmarks.criticality_auto import LARGER  # noqa: E402

HPN, RCHPN = "hpn", "hpn+peephole"


def build(folder: Path, domains: list[str], larger: bool) -> None:
    """``folder/NAME/domain.pddl`` and its problems (auto_ipc's layout)."""
    for d in domains:
        (folder / d).mkdir(parents=True)
        shutil.copy(domain_file(d), folder / d / "domain.pddl")
        for p in instance_files(d):
            shutil.copy(p, folder / d / p.name)
        if larger:
            for k, (params, seed) in enumerate(LARGER.get(d, []), start=1):
                (folder / d / f"q{k:02d}.pddl").write_text(generate(d, params, seed))


def summary(rows: list[dict[str, Any]]) -> str:
    by: dict[str, dict[str, dict[str, Any]]] = defaultdict(dict)
    for r in rows:
        by[r["pair"]][r["setting"]] = r
    per: dict[str, dict[str, Any]] = defaultdict(lambda: {"n": 0, "flat": 0.0, HPN: 0.0, RCHPN: 0.0, "cheaper": 0,
                                                         "same": 0, "dearer": 0, "cpu_h": 0.0, "cpu_r": 0.0,
                                                         "missing": 0, "invalid": 0})
    for pair, rs in sorted(by.items()):
        dom = pair.split("/")[1].split(" ")[0] if "/" in pair else pair
        s = per[dom]
        f, h, c = rs.get("flat"), rs.get(HPN), rs.get(RCHPN)
        if any(x is None for x in (f, h, c)):
            s["missing"] += 1
            continue
        assert f is not None and h is not None and c is not None
        ok = f["outcome"] == "solved" and h["outcome"] == "reached" and c["outcome"] == "reached"
        if not ok:
            s["missing"] += 1
            continue
        s["invalid"] += sum(not str(x.get("validation", "")).startswith("valid") for x in (f, h, c))
        s["n"] += 1
        s["flat"] += f["cost"]
        s[HPN] += h["cost"]
        s[RCHPN] += c["cost"]
        s["cheaper" if c["cost"] < h["cost"] else "same" if c["cost"] == h["cost"] else "dearer"] += 1
        s["cpu_h"] += h["process_cpu_s"]
        s["cpu_r"] += c["process_cpu_s"]
    lines = ["| domain | pairs all solve | flat cost | auto-HPN cost | auto-RCHPN cost | RCHPN below HPN | "
             "cheaper / same / dearer | RCHPN / flat cost | process CPU RCHPN / HPN | not solved by all | "
             "invalid |", "|---|---|---|---|---|---|---|---|---|---|---|"]
    tot: defaultdict[str, float] = defaultdict(float)
    for dom, s in sorted(per.items()):
        dec = 100 * (1 - s[RCHPN] / s[HPN]) if s[HPN] else 0.0
        lines.append(
            f"| {dom} | {s['n']} | {s['flat']:g} | {s[HPN]:g} | {s[RCHPN]:g} | {dec:.1f} % | {s['cheaper']} / "
            f"{s['same']} / {s['dearer']} | {s[RCHPN] / s['flat'] if s['flat'] else 0:.2f} | "
            f"{s['cpu_r'] / s['cpu_h'] if s['cpu_h'] else 0:.2f} | {s['missing']} | {s['invalid']} |")
        for k in ("n", "flat", HPN, RCHPN, "cheaper", "same", "dearer", "cpu_h", "cpu_r", "missing", "invalid"):
            tot[k] += s[k]
    if tot[HPN]:
        lines.append(
            f"| all | {tot['n']:g} | {tot['flat']:g} | {tot[HPN]:g} | {tot[RCHPN]:g} | "
            f"{100 * (1 - tot[RCHPN] / tot[HPN]):.1f} % | {tot['cheaper']:g} / {tot['same']:g} / {tot['dearer']:g} | "
            f"{tot[RCHPN] / tot['flat']:.2f} | {tot['cpu_r'] / tot['cpu_h']:.2f} | {tot['missing']:g} | "
            f"{tot['invalid']:g} |")
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--domains", default=",".join(DOMAINS))
    ap.add_argument("--larger", action="store_true", help="add criticality_auto.py's LARGER instances (qNN)")
    ap.add_argument("--time-limit", type=float, default=60.0)
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "auto_rchpn")
    ap.add_argument("--summarize", type=Path, help="only print the per-domain table of a stored run folder")
    args = ap.parse_args(argv)
    if args.summarize is not None:
        rows = [json.loads(x) for x in (args.summarize / "runs.jsonl").read_text().splitlines() if x.strip()]
        print(summary(rows), end="")
        return 0
    domains = [d for d in args.domains.split(",") if d]
    with tempfile.TemporaryDirectory(prefix="auto-rchpn-") as tmp:
        folder = Path(tmp) / "classical"
        build(folder, domains, args.larger)
        code = auto_ipc.main([str(folder), "--time-limit", f"{args.time_limit:g}", "--problems", "99",
                              "--strategies", f"{HPN},{RCHPN}", "--out", str(args.out)])
    rows = [json.loads(x) for x in (args.out / "runs.jsonl").read_text().splitlines() if x.strip()]
    text = (f"# auto-RCHPN (derived resources) against auto-HPN and flat planning\n\n"
            f"`benchmarks/auto_rchpn.py{' --larger' if args.larger else ''} --time-limit {args.time_limit:g}`; "
            "costs summed over the pairs that flat planning, auto-HPN and auto-RCHPN all solve; process CPU is "
            "each `nowplan` process's, summed (2 shared cores: compare within one run). Per pair: `auto_ipc.md`.\n\n"
            + summary(rows))
    (args.out / "auto_rchpn.md").write_text(text)
    print(text, end="")
    return code


if __name__ == "__main__":
    raise SystemExit(main())
