"""A/B: the executed actions of ``nowplan run`` on PDDL domains without derived predicates, two source trees.

Each run is a process with ``PYTHONPATH`` set to one tree's ``src``; the successful observation events of
its trace are the executed actions.  Prints one line per run and the counts of same / different.

    .venv/bin/python benchmarks/axioms_ab.py /work/main/src src
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

W = Path(__file__).resolve().parents[1]
PY = sys.executable
A, B = sys.argv[1], sys.argv[2]
CLI = "import sys; from nowplan.cli import main; raise SystemExit(main(sys.argv[1:]))"
D = W / "src/nowplan/data/pddl"
T = W / "tests/data/pddl_ipc_style"
cases = []
for n in ("logistics", "gripper", "lights", "blocksworld"):
    for p in sorted((D / n).glob("p0*.pddl"))[:1]:
        cases.append((D / n / "domain.pddl", p))
for n in ("blocks", "miconic", "transport", "zenotravel", "briefcase", "floortile", "miconic-adl"):
    cases.append((T / f"{n}-domain.pddl", T / f"{n}-p01.pddl"))
cases.append((Path("/tmp/ipc9/philosophers/domain.pddl"), Path("/tmp/ipc9/philosophers/p01.pddl")))
settings = [["--strategy", "flat"], ["--criticality", "auto"], ["--criticality", "auto", "--strategy", "hpn+flexible"]]
same = diff = 0
for dom, prob in cases:
    for s in settings:
        outs = []
        for src in (A, B):
            with tempfile.TemporaryDirectory() as tmp:
                tr = Path(tmp) / "t.jsonl"
                r = subprocess.run([PY, "-c", CLI, "run", str(dom), str(prob), "--json", "--trace", str(tr), *s],
                                   capture_output=True, text=True, env={**os.environ, "PYTHONPATH": src}, timeout=300)
                acts = [e["action"] for e in map(json.loads, tr.read_text().splitlines())
                        if e.get("event") == "observation" and e.get("success")] if tr.exists() else None
                outs.append((r.returncode, acts))
        ok = outs[0] == outs[1]
        same += ok; diff += not ok
        print(f"{prob.parent.name}/{prob.name} {' '.join(s)}: {'same' if ok else 'DIFF'} ({len(outs[0][1] or [])} actions, exit {outs[0][0]})", flush=True)
print(f"same {same}, different {diff}")
