"""What the held-out benchmarks (`heldout7.py`, `heldout8.py`, `heldout9.py`) share: the strategies, one guarded run,
the tables and the resumable loop.  Each benchmark names its fault levels and its domains' episodes.
"""

from __future__ import annotations

import argparse
import json
import logging
import signal
import sys
import time
import traceback
from collections import Counter, defaultdict
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

from nowplan.api import NowplanError, Outcome, parse_strategy, run_episode

from bench_args import Hang, alarm, span  # benchmarks/bench_args.py, beside this script

STRATEGIES = [
    "flat", "hpn", "hpn+aggressive", "hpn+flexible", "hpn+foresight", "hpn+monitor", "hpn+monitor-cost",
    "hpn+monitor-goal", "hpn+monitor-restore", "hpn+monitor-rule-cost", "hpn+nodirect", "hpn+noshortcuts",
    "hpn+peephole", "hpn+refine-flat", "hpn+selective", "hpn+serendipity", "online", "online+deferred",
    "online+reuse", "online+reuse+deferred", "hpn+flexible+serendipity+selective+foresight",
    "flat+flexible+serendipity", "hpn+peephole+flexible",
]
def run_one(levels: Mapping[str, tuple[str, dict[str, Any]]], episodes: Mapping[str, Callable[..., Any]],
            level: str, strategy: str, seed: int, max_actions: int, time_limit: float) -> dict[str, Any]:
    domain, kw = levels[level]
    row: dict[str, Any] = {"level": level, "domain": domain, "strategy": strategy, "seed": seed}
    t0, c0 = time.perf_counter(), time.process_time()
    signal.alarm(int(time_limit * 2 + 10))
    try:
        ep = episodes[domain](seed, **kw)
        m = run_episode(ep, parse_strategy(strategy, max_actions=max_actions, time_limit=time_limit), seed=seed)
        row.update(outcome=m.outcome.value, reason=m.reason, actions=m.actions, cycles=m.cycles,
                   goal_in_world=m.goal_in_world, disagreement=list(m.disagreement),
                   execution_cost=round(m.execution_cost, 3), action_counts=dict(m.action_counts),
                   failed_actions=m.failed_actions, exogenous_changes=m.exogenous_changes)
    except Hang:
        row.update(outcome="hang", reason=f"no answer after {time_limit * 2 + 10:g} s", actions=None)
    except NowplanError as e:  # refused before the run, with its one-line reason
        row.update(outcome="refused", reason=str(e), actions=None)
    except Exception as e:  # a crash is what this benchmark looks for
        row.update(outcome="crash", reason=f"{type(e).__name__}: {e}", actions=None,
                   traceback=traceback.format_exc())
    finally:
        signal.alarm(0)
    row["wall_s"] = round(time.perf_counter() - t0, 3)
    row["cpu_s"] = round(time.process_time() - c0, 3)  # (the machine is shared: a wall limit may hit at a few CPU s)
    return row


def table(rows: list[dict[str, Any]]) -> str:
    groups: dict[tuple[str, str], list[dict[str, Any]]] = defaultdict(list)
    for r in rows:
        groups[(r["level"], r["strategy"])].append(r)
    out = ["| level | strategy | runs | reached % | mean actions (reached) | failures (reason: count) |",
           "|---|---|---|---|---|---|"]
    for (level, strategy), rs in sorted(groups.items()):
        ok = [r for r in rs if r["outcome"] == Outcome.REACHED.value]
        acts = sum(r["actions"] for r in ok) / len(ok) if ok else float("nan")
        why = Counter(f"{r['outcome']}: {r['reason'][:90]}" for r in rs if r["outcome"] != "reached")
        out.append(f"| {level} | {strategy} | {len(rs)} | {100 * len(ok) / len(rs):.0f} | {acts:.1f} | "
                   + "; ".join(f"{k} ({n})" for k, n in why.most_common()) + " |")
    return "\n".join(out)


def summary(rows: list[dict[str, Any]]) -> str:
    """Per fault level, over every strategy that was not refused: reached %, crashes, hangs, livelocks."""
    out = ["| level | runs (not refused) | reached % | mean actions | crashes | hangs | livelocks | other failures | refused |",
           "|---|---|---|---|---|---|---|---|---|"]
    for level in sorted({r["level"] for r in rows}):
        rs = [r for r in rows if r["level"] == level]
        run = [r for r in rs if r["outcome"] != "refused"]
        ok = [r for r in run if r["outcome"] == "reached"]
        n = Counter(r["outcome"] for r in run)
        other = len(run) - len(ok) - n["crash"] - n["hang"] - n["livelock"]
        acts = sum(r["actions"] for r in ok) / len(ok) if ok else float("nan")
        out.append(f"| {level} | {len(run)} | {100 * len(ok) / max(len(run), 1):.1f} | {acts:.1f} | {n['crash']} | "
                   f"{n['hang']} | {n['livelock']} | {other} | {len(rs) - len(run)} |")
    return "\n".join(out)


def verdicts(rows: list[dict[str, Any]]) -> str:
    """Per fault level: reached and checked in the world, belief-world disagreements, livelocks,
    crashes, hangs, budget ends (time or actions), other failures, refusals."""
    out = ["| level | runs (not refused) | reached in the world | reached, world unchecked or false | "
           "belief-world disagreement | livelock | crash | hang | limit | other failed | refused |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for level in sorted({r["level"] for r in rows}):
        rs = [r for r in rows if r["level"] == level]
        run = [r for r in rs if r["outcome"] != "refused"]
        ok = [r for r in run if r["outcome"] == "reached" and r.get("goal_in_world") is True]
        n = Counter(r["outcome"] for r in run)
        dis = [r for r in run if r["outcome"] != "reached" and r.get("disagreement")]
        other = n["failed"] - len([r for r in dis if r["outcome"] == "failed"])
        out.append(f"| {level} | {len(run)} | {len(ok)} ({100 * len(ok) / max(len(run), 1):.1f} %) | "
                   f"{n['reached'] - len(ok)} | {len(dis)} | {n['livelock']} | {n['crash']} | {n['hang']} | "
                   f"{n['limit']} | {other} | {len(rs) - len(run)} |")
    return "\n".join(out)


def main(doc: str, levels: Mapping[str, tuple[str, dict[str, Any]]],
         episodes: Callable[[], Mapping[str, Callable[..., Any]]], time_limit: float) -> int:
    """The benchmark's command line; ``episodes()`` imports the domains' scenario functions."""
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--levels", default=",".join(levels))
    ap.add_argument("--strategies", default=",".join(STRATEGIES))
    ap.add_argument("--seeds", default="0-19")
    ap.add_argument("--max-actions", type=int, default=300)
    ap.add_argument("--time-limit", type=float, default=time_limit)
    ap.add_argument("--out", type=Path, help="JSONL; runs already in it are skipped (resume)")
    ap.add_argument("--table", action="store_true", help="only print the table of --out")
    ap.add_argument("--recheck", type=Path, help="re-run every run of --out that ended 'limit' with --time-limit, "
                    "writing the rows here (resumable): was it the machine's load or the run?")
    a = ap.parse_args()
    signal.signal(signal.SIGALRM, alarm)
    logging.getLogger("nowplan").setLevel(logging.ERROR)  # the runs' warnings are not the table's
    done: list[dict[str, Any]] = []
    if a.out and a.out.exists():
        done = [json.loads(x) for x in a.out.read_text().splitlines() if x.strip()]
    if a.recheck:
        eps = episodes()
        again = [json.loads(x) for x in a.recheck.read_text().splitlines() if x.strip()] if a.recheck.exists() else []
        seen = {(r["level"], r["strategy"], r["seed"]) for r in again}
        for r in done:
            if r["outcome"] == "limit" and (r["level"], r["strategy"], r["seed"]) not in seen:
                row = run_one(levels, eps, r["level"], r["strategy"], r["seed"], a.max_actions, a.time_limit)
                again.append(row)
                with a.recheck.open("a") as fh:
                    fh.write(json.dumps(row) + "\n")
        print(verdicts(again) + "\n\n" + table(again))
        return 0
    if not a.table:
        eps = episodes()
        have = {(r["level"], r["strategy"], r["seed"]) for r in done}
        for level in a.levels.split(","):
            for strategy in a.strategies.split(","):
                for seed in span(a.seeds):
                    if (level, strategy, seed) in have:
                        continue
                    row = run_one(levels, eps, level, strategy, seed, a.max_actions, a.time_limit)
                    done.append(row)
                    if a.out:
                        with a.out.open("a") as fh:
                            fh.write(json.dumps(row) + "\n")
                    if row["outcome"] != "reached":
                        print(f"{level} {strategy} s{seed}: {row['outcome']}: {row['reason'][:160]}",
                              file=sys.stderr, flush=True)
    print(verdicts(done) + "\n\n" + summary(done) + "\n\n" + table(done))
    return 0
