"""A/B of two source trees on the same runs: does a change leave every run's decisions as they were?

Made for the change that has the online policy use the executive's progress guard (acting/guard.py)
instead of its own copy, but it compares any two commits.  Both trees are taken from ``git archive``
snapshots (so neither working tree is touched), and each is run in its own worker process, one
after the other (one process at a time), over the same matrix of domain x fault level x strategy x
seed.  A run's record: its outcome, reason, action count, cycles seen, the executed action sequence
and a digest of its whole trace with the timing fields left out.  The two sets are then diffed run
for run and the table is written to ``--results`` (default benchmarks/results/guard_ab/).

    python benchmarks/guard_ab.py --a main --b wip-guard9 --seeds 0-9          # the online strategies
    python benchmarks/guard_ab.py --a main --b wip-guard9 --hpn --seeds 0-2    # a sample of the executive's

Each worker's JSONL is resumable: runs already in it are skipped.  Timing can still make a run
differ (a planner call or a run that reaches its time limit); such runs are marked in the table
(``timed``) and not counted as a difference of the code.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import logging
import os
import re
import signal
import subprocess
import sys
import time
import traceback
from collections import Counter
from pathlib import Path
from typing import Any

from bench_args import Hang, alarm, span  # benchmarks/bench_args.py, beside this script

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ("lab", "search", "drone", "ward", "house")
ONLINE = ("online", "online+reuse", "online+deferred", "online+reuse+deferred")
HPN_SAMPLE = ("hpn", "hpn+aggressive", "hpn+monitor", "hpn+flexible+serendipity+selective+foresight")
# registered domains: (scenario, fault levels as sweep scenario suffixes, see nowplan.experiments.faults)
REGISTERED: dict[str, tuple[str, tuple[str, ...]]] = {
    "logistics": ("small", ("", "failure=0.25", "exogenous=0.25", "failure=0.5&exogenous=0.5")),
    "marsupial": ("single-3", ("", "failure=0.25")),  # (refuses the online policy: its loader's work)
    "pieces": ("tiny-disturbed", ("", "exogenous=0.25", "exogenous=0.5", "miss=0.3")),  # (no action failures)
    "namo": ("domain1", ("", "failure=0.25", "exogenous=0.25", "failure=0.5&exogenous=0.5")),
    "kitchen": ("cook", ("", "failure=0.25")),
}
# the held-out example domains: fault levels as keyword arguments of their scenarios' episode()
# (a selection of benchmarks/heldout7.py's and heldout8.py's levels)
HELDOUT: dict[str, dict[str, dict[str, Any]]] = {
    "lab": {"clean": {}, "f0.2-sticky0.3": {"failure_prob": 0.2, "sticky": 0.3},
            "f0.5-x0.5": {"failure_prob": 0.5, "exogenous_prob": 0.5, "sticky": 0.3}},
    "search": {"clean": {}, "f0.2-m0.2": {"failure_prob": 0.2, "miss": 0.2},
               "f0.5-x0.5-m0.3": {"failure_prob": 0.5, "exogenous_prob": 0.5, "miss": 0.3}},
    # (drone f0.5-x0.5-n0.3-m0.3 runs into the time limit while planning: a comparison of timing, not of code)
    "drone": {"clean": {}, "f0.2-slip0.1": {"failure_prob": 0.2, "slip": 0.1},
              "x0.2-n0.15-m0.2": {"exogenous_prob": 0.2, "fix_sigma": 0.15, "miss": 0.2, "slip": 0.2}},
    "ward": {"clean": {}, "f0.2": {"failure_prob": 0.2},
             "f0.5-x0.5-n0.2-m0.3": {"failure_prob": 0.5, "exogenous_prob": 0.5, "noise": 0.2, "miss": 0.3}},
    "house": {"clean": {}, "f0.2-sticky0.3": {"failure_prob": 0.2, "sticky": 0.3},
              "f0.5-x0.5": {"failure_prob": 0.5, "exogenous_prob": 0.5}},
}
TIMING = frozenset({"t", "cpu_s", "wall_s", "planning_cpu_s", "planning_s", "version"})


def cells(domains: list[str], strategies: tuple[str, ...], seed_list: list[int]) -> list[tuple[str, str, str, int]]:
    out = []
    for d in domains:
        levels = list(HELDOUT[d]) if d in HELDOUT else [lv or "none" for lv in REGISTERED[d][1]]
        for level in levels:
            for s in strategies:
                for seed in seed_list:
                    out.append((d, level, s, seed))
    return out


def _strip(x: Any) -> Any:
    if isinstance(x, dict):
        return {k: _strip(v) for k, v in x.items() if k not in TIMING}
    if isinstance(x, list):
        return [_strip(v) for v in x]
    return x


def _episode(domain: str, level: str, seed: int) -> tuple[Any, Any]:
    """The episode and the planner the domain's spec names (None for a held-out domain)."""
    if domain in HELDOUT:
        import importlib

        mod = importlib.import_module(f"{domain}_domain.scenarios")
        return mod.episode(seed, **HELDOUT[domain][level]), None
    from nowplan.domains.registry import get_domain
    from nowplan.experiments.faults import apply_faults, split_scenario

    base = REGISTERED[domain][0]
    _, faults = split_scenario(base if level == "none" else f"{base}?{level}")
    spec = get_domain(domain)
    ep = spec.scenario(base)(seed)
    apply_faults(ep, faults)
    return ep, spec.planner


def run_one(domain: str, level: str, strategy: str, seed: int, max_actions: int, time_limit: float) -> dict[str, Any]:
    from nowplan.api import NowplanError, parse_strategy, run_episode
    from nowplan.trace import Trace

    row: dict[str, Any] = {"domain": domain, "level": level, "strategy": strategy, "seed": seed}
    t0 = time.perf_counter()
    signal.alarm(int(time_limit * 2 + 10))
    trace = Trace()
    try:
        ep, planner = _episode(domain, level, seed)
        kw = {"base_planner": planner} if planner is not None else {}
        st = parse_strategy(strategy, max_actions=max_actions, time_limit=time_limit, **kw)
        m = run_episode(ep, st, seed=seed, trace=trace)
        row.update(outcome=m.outcome.value, reason=m.reason, actions=m.actions, cycles=m.cycles)
    except Hang:
        row.update(outcome="hang", reason=f"no answer after {time_limit * 2 + 10:g} s", actions=None)
    except NowplanError as e:
        row.update(outcome="refused", reason=str(e), actions=None)
    except Exception as e:
        row.update(outcome="crash", reason=f"{type(e).__name__}: {e}", actions=None, traceback=traceback.format_exc())
    finally:
        signal.alarm(0)
    row["wall_s"] = round(time.perf_counter() - t0, 3)
    row["sequence"] = [e["action"] for e in trace.events if e["event"] == "action"]
    row["notes"] = [e["text"] for e in trace.events if e["event"] == "note" and str(e["text"]).startswith("progress")]
    digest = hashlib.sha256(json.dumps(_strip(trace.events), sort_keys=True, default=str).encode()).hexdigest()
    row["trace_digest"] = digest[:16]
    # a run that may have reached a time limit (its own or a planner call's) may differ by timing alone
    row["timed"] = ("time limit" in row.get("reason", "") or row["outcome"] == "hang"
                    or any(e.get("status") == "time_limit" for e in trace.events if e["event"] == "plan_failed"))
    return row


def worker(a: argparse.Namespace) -> int:
    import nowplan

    signal.signal(signal.SIGALRM, alarm)
    logging.getLogger("nowplan").setLevel(logging.ERROR)
    print(f"worker: nowplan from {nowplan.__file__}", file=sys.stderr, flush=True)
    out = Path(a.out)
    have = set()
    if out.exists():
        have = {(r["domain"], r["level"], r["strategy"], r["seed"]) for r in map(json.loads, out.read_text().splitlines())}
    todo = json.loads(Path(a.cells).read_text())
    for d, level, s, seed in todo:
        if (d, level, s, seed) in have:
            continue
        row = run_one(d, level, s, seed, a.max_actions, a.time_limit)
        row["nowplan"] = nowplan.__file__
        with out.open("a") as fh:
            fh.write(json.dumps(row) + "\n")
    return 0


def snapshot(ref: str, into: Path) -> tuple[str, Path]:
    sha = subprocess.run(["git", "-C", str(ROOT), "rev-parse", ref], check=True, capture_output=True,
                         text=True).stdout.strip()
    tree = into / sha[:10]
    if not (tree / "src" / "nowplan").exists():
        tree.mkdir(parents=True, exist_ok=True)
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", sha, "src", "examples"], check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    return sha, tree


_FROZEN = re.compile(r"frozenset\(\{([^{}]*)\}\)")


def _canonical(action: str) -> str:
    """An action's text with its sets' elements sorted (their printed order follows string hashing,
    which differs from process to process unless PYTHONHASHSEED is set)."""
    return _FROZEN.sub(lambda m: "frozenset({" + ", ".join(sorted(m.group(1).split(", "))) + "})", action)


def compare(ra: dict[tuple[Any, ...], dict[str, Any]], rb: dict[tuple[Any, ...], dict[str, Any]]) -> list[dict[str, Any]]:
    out = []
    for k in sorted(set(ra) & set(rb), key=str):
        x, y = ra[k], rb[k]
        sa, sb = [_canonical(t) for t in x["sequence"]], [_canonical(t) for t in y["sequence"]]
        diff = [f for f in ("outcome", "reason", "actions") if x.get(f) != y.get(f)] + (["sequence"] if sa != sb else [])
        n = min(len(sa), len(sb))
        out.append({"key": k, "a": x, "b": y, "diff": diff, "trace_same": x["trace_digest"] == y["trace_digest"],
                    "timed": x["timed"] or y["timed"], "prefix": sa[:n] == sb[:n]})
    return out


def report(rows: list[dict[str, Any]], sha_a: str, sha_b: str, label: str) -> str:
    groups: dict[tuple[str, str], Counter[str]] = {}
    for r in rows:
        d, _, s, _ = r["key"]
        c = groups.setdefault((d, s), Counter())
        c["runs"] += 1
        c["same"] += not r["diff"]
        c["trace"] += r["trace_same"]
        c["timed"] += r["timed"]
        c["timed_diff"] += bool(r["diff"]) and r["timed"] and r["prefix"]
        c["reached"] += r["a"]["outcome"] == "reached"
        c["livelock"] += r["a"]["outcome"] == "livelock"
        c["cycles"] += bool(r["a"].get("cycles"))
        c["commit"] += any("committing" in n for n in r["a"].get("notes", []))
    n = len(rows)
    same = sum(not r["diff"] for r in rows)
    timed = sum(bool(r["diff"]) and r["timed"] and r["prefix"] for r in rows)
    lines = [f"## {label}: {sha_a[:10]} (a) vs {sha_b[:10]} (b)", "",
             f"{n} runs compared; {same} identical in outcome, reason, action count and executed action sequence; "
             f"{sum(r['trace_same'] for r in rows)} with identical traces (timing fields left out); {timed} differ only "
             "where a time limit cut one of them short (one's executed actions are a prefix of the other's); "
             f"{n - same - timed} other differences.", "",
             "| domain | strategy | runs | identical | same trace | timed, prefix-consistent | runs with a cycle "
             "| with a commitment | reached (a) | livelock (a) | timed (a or b) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for (d, s), c in sorted(groups.items()):
        lines.append(f"| {d} | {s} | {c['runs']} | {c['same']} | {c['trace']} | {c['timed_diff']} | {c['cycles']} | "
                     f"{c['commit']} | {c['reached']} | {c['livelock']} | {c['timed']} |")
    diffs = [r for r in rows if r["diff"] or not r["trace_same"]]
    if diffs:
        lines += ["", "Runs that differ:", ""]
        for r in diffs:
            a, b = r["a"], r["b"]
            lines.append(f"* {' '.join(map(str, r['key']))}: fields {r['diff'] or '(trace only)'}"
                         f"{' (timed)' if r['timed'] else ''}{' (prefix-consistent)' if r['prefix'] else ''}; "
                         f"a: {a['outcome']} {a['actions']} actions, "
                         f"b: {b['outcome']} {b['actions']} actions; a reason: {a['reason'][:200]}; "
                         f"b reason: {b['reason'][:200]}")
    return "\n".join(lines) + "\n"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] if __doc__ else "")
    ap.add_argument("--a", default="main")
    ap.add_argument("--b", default="HEAD")
    ap.add_argument("--domains", default="logistics,pieces,namo,lab,search,ward,house,drone,marsupial")
    ap.add_argument("--strategies", default=",".join(ONLINE))
    ap.add_argument("--hpn", action="store_true", help="the executive's sample of strategies instead")
    ap.add_argument("--seeds", default="0-9")
    ap.add_argument("--max-actions", type=int, default=200)
    ap.add_argument("--time-limit", type=float, default=30.0)
    ap.add_argument("--label", default="online")
    ap.add_argument("--snapshots", type=Path, default=Path("/tmp/guard_ab"))
    ap.add_argument("--results", type=Path, default=ROOT / "benchmarks" / "results" / "guard_ab")
    ap.add_argument("--report-only", action="store_true", help="only diff the stored runs of --a and --b")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    ap.add_argument("--cells", help=argparse.SUPPRESS)
    ap.add_argument("--out", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.worker:
        return worker(a)
    strategies = HPN_SAMPLE if a.hpn else tuple(a.strategies.split(","))
    todo = cells(a.domains.split(","), strategies, span(a.seeds))
    a.results.mkdir(parents=True, exist_ok=True)
    cells_file = a.results / f"{a.label}_cells.json"
    cells_file.write_text(json.dumps(todo))
    recs: list[dict[tuple[Any, ...], dict[str, Any]]] = []
    shas = []
    for ref in (a.a, a.b):
        sha, tree = snapshot(ref, a.snapshots)
        shas.append(sha)
        out = a.results / f"{a.label}_{sha[:10]}.jsonl"
        path = os.pathsep.join([str(tree / "src"), *(str(tree / "examples" / e) for e in EXAMPLES)])
        # (the online runs stored were made without a fixed PYTHONHASHSEED: see _canonical)
        env = {**os.environ, "PYTHONPATH": path, "PYTHONHASHSEED": os.environ.get("PYTHONHASHSEED", "0")}
        cmd = [sys.executable, __file__, "--worker", "--cells", str(cells_file), "--out", str(out),
               "--max-actions", str(a.max_actions), "--time-limit", str(a.time_limit)]
        if not a.report_only:
            subprocess.run(cmd, check=True, env=env)
        want = set(map(tuple, todo))
        rows = [json.loads(x) for x in out.read_text().splitlines()]
        recs.append({k: r for r in rows if (k := (r["domain"], r["level"], r["strategy"], r["seed"])) in want})
    rows = compare(recs[0], recs[1])
    text = report(rows, shas[0], shas[1], a.label)
    (a.results / f"{a.label}.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
