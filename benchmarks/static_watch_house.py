"""The static watch (acting/static_watch.py) on a domain it was not tuned on: the house (examples/house)
remodelled mid-run. After the 2nd or the 5th action the kitchen's door to the hall is walled up and the
bath's door now also opens into the kitchen (static `connects` facts, reported as an exogenous change).
Seeds 0-5 x two moments per strategy: runs reached, actions failed, actions taken.

    PYTHONPATH=src .venv/bin/python benchmarks/static_watch_house.py
"""
import sys
from pathlib import Path
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "examples" / "house"))
from house_domain.scenarios import problem
from house_domain.model import DOMAIN
from nowplan.api import Episode, SymbolicBelief, SymbolicWorld, atom, parse_strategy, run_episode

def make(seed, at):
    prob = problem(seed)
    n = {"k": 0}
    def remodel(state, rng):
        n["k"] += 1
        if n["k"] != at:
            return []
        return [atom("connects", "d_kitchen", "hall", "kitchen", value=False),
                atom("connects", "d_kitchen", "kitchen", "hall", value=False),
                atom("connects", "d_bath", "bath", "kitchen"), atom("connects", "d_bath", "kitchen", "bath")]
    world = SymbolicWorld(DOMAIN, prob.init, seed=seed + 1, exogenous=remodel, exogenous_prob=1.0)
    return Episode(prob, world, SymbolicBelief(prob.init), "remodel")

for s in ("flat", "hpn", "hpn+peephole", "hpn+flexible+serendipity+selective"):
    out = []
    for seed in range(6):
        for at in (2, 5):
            m = run_episode(make(seed, at), parse_strategy(s, max_actions=200, time_limit=20), seed=seed)
            out.append((m.outcome.value[:4], m.actions, m.failed_actions))
    ok = sum(o[0] == "reac" for o in out)
    print(s, ok, "of", len(out), "failed actions", sum(o[2] for o in out), "actions", sum(o[1] for o in out), [o for o in out if o[0] != "reac"][:3])
