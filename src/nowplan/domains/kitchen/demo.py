"""``nowplan demo kitchen``: one task solved by the online policy, with camera frames and a GIF.

``--scenario`` picks the task (inspect, stow, swap or cook; default inspect) and ``--seed`` the problem.
"""

from __future__ import annotations

import argparse
from typing import Any

from nowplan.acting.online import OnlinePolicy
from nowplan.domains.kitchen.render import data_uri, render_png
from nowplan.domains.kitchen.heuristic import estimate_in_actions
from nowplan.domains.kitchen.repro import CAP_S, kitchen_strategy
from nowplan.domains.kitchen.tasks import make
from nowplan.trace import Trace
from nowplan.viz.animation import write_captioned_gif
from nowplan.viz.viewer import write_viewer



def main(args: argparse.Namespace) -> int:
    index = getattr(args, "seed", 0) % 25
    task = getattr(args, "scenario", None) or "inspect"
    ep = make(task, index)
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"nowplan demo kitchen: {ep.description}")
    print(f"goal: {ep.problem.goal}\n")
    frames: list[bytes] = []
    captions: list[str] = []
    trace_path = args.out / "trace.jsonl"
    with Trace(trace_path) as trace:
        first = render_png(ep.world, ep.belief)
        frames.append(first)
        captions.append("start: camera view and prior particles")
        trace.emit("frame", n=0, image=data_uri(first), caption=captions[-1])

        def after_action(tr: Any, action: Any, obs: Any) -> None:
            png = render_png(ep.world, ep.belief)
            frames.append(png)
            captions.append(f"after {action}" + ("" if obs.success else " (failed)"))
            tr.emit("frame", n=len(frames) - 1, image=data_uri(png), caption=captions[-1])
            print(f"  {action}  -> {'ok' if obs.success else 'failed'}"
                  + (f", seen: {', '.join(obs.info.get('seen', [])) or 'nothing'}" if action.name == "detect" else ""))

        ep.belief.after_action = after_action
        strategy = kitchen_strategy("online+reuse+deferred", CAP_S, max_actions=60)
        ep.belief.planning_heuristic = estimate_in_actions  # the greedy search's estimate (as the reproduction's)
        metrics = OnlinePolicy(ep.problem, ep.world, ep.belief, strategy, seed=index, trace=trace).run()
        trace.emit("run_end", outcome=metrics.outcome.value, reason=metrics.reason, metrics=metrics.to_dict())
    header = (f"Kitchen, {task} (seed 004's SS-Replan): the fixed camera's view; dots are the belief's "
              "particles for each object, in its colour, brighter where likelier.")
    gif = write_captioned_gif(frames, args.out / "kitchen.gif", header, captions, scale=2.0)
    page = write_viewer(trace_path, args.out / "trace.html")
    print()
    print(metrics.summary())
    print(f"\ntrace: {trace_path}\nanimation: {gif}\nviewer: {page} (open it in a browser)")
    return 0 if metrics.outcome.value == "reached" else 1
