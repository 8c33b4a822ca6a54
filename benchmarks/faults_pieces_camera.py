"""Pieces (seed 003) under harsher camera noise than the scenarios' (issue 14 stress probe; no fault knob).

    PYTHONPATH=src python benchmarks/faults_pieces_camera.py harsh,harsher hpn,hpn+flexible,online+reuse+deferred 0 4

args: noise levels, strategies, first seed, end seed (tiny board, disturbance 0.2); prints one line per run:
noise, strategy, seed, outcome, actions, wall s, goal holds in the world, reason.
"""
import sys, time, logging
from nowplan.acting.run import run_episode
from nowplan.acting.strategy import parse_strategy
from nowplan.domains.pieces.scenarios import SIZES, generate, make_episode
from nowplan.domains.pieces.render import CameraNoise
noises = {
 "harsh": CameraNoise(jitter=0.12, rotation_deg=20.0, pixel_sigma=(8.0, 25.0), occlusion_prob=0.5, shake=5),
 "harsher": CameraNoise(jitter=0.15, rotation_deg=25.0, brightness=(0.4, 1.5), gradient=0.5, pixel_sigma=(15.0, 35.0), occlusion_prob=0.7, occluder_cells=(0.8, 2.0), shake=6),
}
strats = sys.argv[2].split(",")
seeds = range(int(sys.argv[3]), int(sys.argv[4]))
for nn in sys.argv[1].split(","):
  for st in strats:
    for seed in seeds:
        task = generate(SIZES["tiny"], seed, "pieces-tiny")
        ep = make_episode(task, seed, 0.2, noise=noises[nn])
        t = time.time()
        try:
            m = run_episode(ep, parse_strategy(st, time_limit=30.0), seed=seed)
            print(nn, st, seed, m.outcome.value, m.actions, round(time.time()-t, 1), m.goal_in_world, m.reason[:150], flush=True)
        except Exception as e:
            print(nn, st, seed, "CRASH", repr(e)[:200], flush=True)
