"""``nowplan reproduce 004``: Table I's four variants on the four kitchen tasks.

Each trial runs the online policy on one generated problem with a cap on
total planning time (CPU seconds of the policy's process).  The paper
allowed 10 minutes per policy on its machine with IKFast and PDDLStream;
our planner is in-process, so the cap is scaled down to ``HARD_CAP_S``
seconds for the hard distribution (:mod:`~nowplan.domains.kitchen.hard`, the
default) and ``CAP_S`` (``QUICK_CAP_S`` quick) for the original problems
(``--easy``, :mod:`~nowplan.domains.kitchen.tasks`).  Success is the goal
belief holding within the cap and 40 actions; time is the mean total
planning time (regression, stream binding, IK and motion planning) over
successful trials.  The quick run has problems 0–2 of each task, ``--full``
0–24, ``--trials N`` 0–(N−1); ``--runs FILE`` keeps every trial (JSON lines)
so that a run can be resumed or done in pieces.
"""

from __future__ import annotations

import logging
import statistics
from typing import Any

from nowplan.experiments import progress
from nowplan.experiments.reproductions import (
    ReproductionOptions,
    ReproductionResult,
    ReproStatus,
    side_by_side,
)
from nowplan.experiments.verdicts import Comparison, Verdict, judged

log = logging.getLogger(__name__)

VARIANTS = {"neither": "online", "constraints": "online+reuse", "deferred": "online+deferred",
            "both": "online+reuse+deferred"}
TASK_NAMES = {"inspect": "Inspect", "stow": "Stow", "swap": "Swap", "cook": "Cook"}
CAP_S = 30.0  # the easy set (--easy): 600 s x 0.05
QUICK_CAP_S = 15.0
HARD_CAP_S = 30.0  # the hard distribution: 600 s x 0.05 of CPU time
HARD_QUICK_CAP_S = 30.0
PROBLEMS = 25
QUICK_PROBLEMS = 3
PAPER_CAP_S = 600.0
SEARCH_WEIGHT = 10.0
MAX_NODES = 3000
GENERATOR_VALUES = 4
MAX_ACTIONS = 40  # a trial's action budget (the paper has none; ours keeps a lost policy from running on)
# The hard distribution's budget.  The paper bounds a trial by its planning-time cap alone; our budget is
# a guard (loops are caught by the progress guard's cycle and livelock verdicts).  On the hard
# distribution a policy may have to search three containers for the block before it finds it behind
# the soup can, and Swap then needs ~20 more actions: a trial that did so took 45 actions (Swap 2,
# Both), so 40 ended trials that were making progress.  60 leaves that room and still stops a policy
# that has lost its way.
HARD_MAX_ACTIONS = 60


def kitchen_strategy(switches: str, cap: float, max_actions: int = 40) -> Any:
    """The strategy for one kitchen policy: ``switches`` with a total planning cap of ``cap`` seconds.

    The regression search is greedy (weight ``SEARCH_WEIGHT`` on the count-of-unmet-atoms
    heuristic), like the greedy Fast Downward configurations PDDLStream uses; each call may
    expand ``MAX_NODES`` nodes, and each generator contributes up to ``GENERATOR_VALUES``
    values per sample-pool level.  The cap is on this process's CPU time (``clock="cpu"``):
    on a machine shared with other jobs wall time would charge a policy for their load.
    """
    from dataclasses import replace

    from nowplan.acting.strategy import parse_strategy

    strategy = parse_strategy(switches, time_limit=cap, max_actions=max_actions)
    planner = replace(strategy.planner, time_limit=cap, max_nodes=MAX_NODES, max_generator_values=GENERATOR_VALUES,
                      weight=SEARCH_WEIGHT, serialization=False, monotonic=False, clock="cpu")
    return replace(strategy, planner=planner)


def trial(task: str, index: int, variant: str, cap: float, seed: int = 0, easy: bool = False,
          max_actions: int | None = None) -> dict[str, Any]:
    """One policy on one problem: the hard distribution (:mod:`~nowplan.domains.kitchen.hard`), or
    with ``easy`` the original one (:mod:`~nowplan.domains.kitchen.tasks`)."""
    from nowplan.acting.online import OnlinePolicy
    from nowplan.domains.kitchen import hard, tasks
    from nowplan.domains.kitchen.heuristic import estimate_in_actions

    ep = (tasks.make if easy else hard.make)(task, index, seed)
    ep.belief.planning_heuristic = estimate_in_actions  # (a greedy search's estimate: see its docstring)
    if max_actions is None:
        max_actions = MAX_ACTIONS if easy else HARD_MAX_ACTIONS
    strategy = kitchen_strategy(VARIANTS[variant], cap, max_actions)
    pol = OnlinePolicy(ep.problem, ep.world, ep.belief, strategy, seed=index, reuse_budget=min(3.0, cap / 5))
    try:
        m = pol.run()
    finally:
        from nowplan.domains.kitchen.scene import close

        close(ep.world.scene)
        close(ep.belief.scene)
    return {"task": task, "index": index, "variant": variant, "outcome": m.outcome.value, "reason": m.reason,
            "planning_s": pol.planning_s, "actions": m.actions,
            "motion_calls": ep.belief.streams.calls["motion"], "max_actions": max_actions}


def _plan_trials(options: ReproductionOptions) -> tuple[int, float, list[tuple[str, int, str]]]:
    n = options.trials or (QUICK_PROBLEMS if options.quick else PROBLEMS)
    cap = (QUICK_CAP_S if options.quick else CAP_S) if options.easy else (HARD_QUICK_CAP_S if options.quick else HARD_CAP_S)
    return n, cap, [(task, k, v) for task in TASK_NAMES for v in VARIANTS for k in range(n)]


def _key(easy: bool, cap: float, task: str, index: int, variant: str) -> str:
    return f"{'easy' if easy else 'hard'}/{cap:g}/{task}/{index}/{variant}"


def _stored(path: Any) -> dict[str, dict[str, Any]]:
    """The trials already in a JSON-lines runs file, by key (a damaged line is skipped with a warning)."""
    import json

    out: dict[str, dict[str, Any]] = {}
    if path is None or not path.exists():
        return out
    for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        try:
            rec = json.loads(line)
            out[str(rec["key"])] = rec
        except (ValueError, KeyError, TypeError):
            log.warning("%s line %d: not a stored 004 trial; skipped", path, i)
    return out


def _one(job: tuple[str, int, str, float, bool]) -> dict[str, Any]:
    task, k, variant, cap, easy = job
    rec = trial(task, k, variant, cap, easy=easy)
    rec["key"] = _key(easy, cap, task, k, variant)
    rec["cap_s"] = cap
    rec["distribution"] = "easy" if easy else "hard"
    return rec


def run(options: ReproductionOptions) -> ReproductionResult:
    """Table I on the hard distribution (the default) or, with ``options.easy``, the original one.

    ``options.trials`` sets the problems per task; ``options.runs_file`` (JSON lines) keeps every
    finished trial and skips those it holds (resume, or run a table in pieces); ``options.stored_only``
    runs nothing; ``options.jobs`` worker processes (default 1).
    """
    import json

    n, cap, plan = _plan_trials(options)
    easy = options.easy
    stored = _stored(options.runs_file)
    todo = [(t, k, v, cap, easy) for t, k, v in plan if _key(easy, cap, t, k, v) not in stored]
    if options.stored_only:
        todo = []
    done: dict[str, dict[str, Any]] = {}
    bar = progress.bar(len(todo), "reproduce 004", unit="trial")

    def keep(rec: dict[str, Any]) -> None:
        done[rec["key"]] = rec
        if options.runs_file is not None:
            with options.runs_file.open("a", encoding="utf-8") as fh:
                fh.write(json.dumps(rec, default=str) + "\n")
        bar.set_postfix_str(f"{rec['task']} {rec['variant']}", refresh=False)
        bar.update(1)

    jobs = max(1, options.jobs or 1)
    if jobs > 1 and len(todo) > 1:
        import multiprocessing

        with multiprocessing.get_context("spawn").Pool(jobs) as pool:
            for rec in pool.imap_unordered(_one, todo):
                keep(rec)
    else:
        for job in todo:
            keep(_one(job))
    bar.close()
    got = {**stored, **done}
    trials = [got[_key(easy, cap, t, k, v)] for t, k, v in plan if _key(easy, cap, t, k, v) in got]
    rows = table_rows(trials)
    which = "easy set (the original problems)" if easy else "hard distribution (nowplan.domains.kitchen.hard)"
    counts = sorted({sum(1 for t in trials if t["task"] == task and t["variant"] == v)
                     for task in TASK_NAMES for v in VARIANTS})
    notes = (
        f"{which}; problems per task: {'/'.join(map(str, counts)) if counts else 0} (asked {n}); per-trial planning "
        f"cap {cap:g} s of CPU time, scaled from the paper's {PAPER_CAP_S:g} s by {cap / PAPER_CAP_S:.3g}; "
        f"{MAX_ACTIONS if easy else HARD_MAX_ACTIONS} actions at most (the paper has no action budget); times are the policy process's CPU seconds of planning (search, stream binding, IK "
        "and motion planning) on this machine, not comparable in absolute terms. Failure reasons: "
        + "; ".join(sorted({f"{t['task']}/{t['variant']}: {t['reason']}" for t in trials if t['outcome'] != 'reached'}))[:1500]
    )
    from nowplan.experiments.papers import PAPERS

    paper = [dict(r) for r in PAPERS["004"].rows]
    result = ReproductionResult("004", ReproStatus.DONE, rows=rows, notes=notes,
                                comparisons=comparisons(rows, paper))
    result.paper = paper
    if options.out_dir is not None:
        from nowplan.experiments.report import Block, Heading, Paragraph, write_report

        out = options.out_dir
        out.mkdir(parents=True, exist_ok=True)
        blocks: list[Block] = [
            Heading("Seed 004, Table I: ours beside the paper's", 1),
            side_by_side(rows, paper, ["task", "algorithm"], "success rate (%) and mean planning time (s) of "
                         "successful trials"),
            Paragraph(notes),
        ]
        files = write_report(blocks, out)
        runs = out / "runs_004.json"
        runs.write_text(json.dumps(trials, indent=1, default=str), encoding="utf-8")
        result.outputs.extend([files.markdown, files.html, runs])
    return result


def table_rows(trials: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """One row per task and variant: success % and the mean planning time of successful trials."""
    rows = []
    for task, label in TASK_NAMES.items():
        for variant in VARIANTS:
            res = [t for t in trials if t["task"] == task and t["variant"] == variant]
            if not res:
                continue
            ok = [r for r in res if r["outcome"] == "reached"]
            rows.append({
                "task": label, "algorithm": variant, "problems": len(res),
                "success_pct": round(100.0 * len(ok) / len(res), 1),
                "planning_time_s": round(statistics.mean(r["planning_s"] for r in ok), 2) if ok else None,
            })
    return rows


BOTH_AT_LEAST = 95.0  # issue 17: Both's success % on every task
GAP_POINTS = 20.0  # Neither below Both by at least this many points ...
GAP_TASKS = 2  # ... on at least this many tasks


def comparisons(rows: list[dict[str, Any]], paper: list[dict[str, Any]]) -> list[Comparison]:
    """Issue 17's targets: Both >= 95 % on every task; Neither below Both by >= 20 points on at least
    two tasks; on every task Constraints and Deferred each between Neither and Both."""
    ours = {(r["task"], r["algorithm"]): r["success_pct"] for r in rows}
    theirs = {(r["task"], r["algorithm"]): r["success_pct"] for r in paper}
    out = []
    gaps = []
    for label in TASK_NAMES.values():
        if any((label, v) not in ours for v in VARIANTS):
            continue
        n, c, d, b = (ours[(label, v)] for v in VARIANTS)
        out.append(judged(f"{label}: Both success %", b, theirs.get((label, "both")), at_least=BOTH_AT_LEAST,
                          target=f">= {BOTH_AT_LEAST:g}"))
        gaps.append(b - n)
        ok = n <= min(c, d) and max(c, d) <= b
        out.append(Comparison(
            f"{label}: success % Neither / Constraints / Deferred / Both", None, None,
            Verdict.MET if ok else Verdict.NOT_MET, "Neither <= Constraints, Deferred <= Both",
            ours_text=" / ".join(f"{ours[(label, v)]:g}" for v in VARIANTS),
            paper_text=" / ".join(f"{theirs[(label, v)]:g}" for v in VARIANTS if (label, v) in theirs)))
    if gaps:
        wide = sum(g >= GAP_POINTS for g in gaps)
        paper_wide = sum(theirs[(t, "both")] - theirs[(t, "neither")] >= GAP_POINTS for t in TASK_NAMES.values())
        out.append(judged(f"tasks where Neither is >= {GAP_POINTS:g} points below Both", float(wide),
                          float(paper_wide), at_least=float(GAP_TASKS), target=f">= {GAP_TASKS}",
                          ours_text=f"{wide} (gaps {' / '.join(f'{g:g}' for g in gaps)})"))
    return out
