"""Start-up CPU of ``nowplan plan`` and ``nowplan run`` as processes, two source trees alternating.

For each tree (``--tree LABEL=SRC``, the ``src`` folder put first on ``PYTHONPATH``) and each command
this runs ``--repeats`` child processes, alternating trees and commands in one loop so a change of the
machine's load reaches every cell alike, and reports the median of each cell's child CPU (user+sys
from ``os.wait4``).  The commands: ``import`` (``import nowplan.cli``, the interpreter plus the entry
point), ``plan`` (``nowplan plan D P --json --improve 0``) and ``run`` (``nowplan run D P --criticality
auto --strategy hpn --json``) on the given small pair.

    .venv/bin/python benchmarks/startup_cpu.py --tree before=/tmp/a/src --tree after=src \\
        /tmp/ipc8/visitall/domain.pddl /tmp/ipc8/visitall/p02.pddl --repeats 15
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import time

CLI = "import sys; from nowplan.cli import main; raise SystemExit(main(sys.argv[1:]))"


def cpu_of(cmd: list[str], env: dict[str, str]) -> float:
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"{' '.join(cmd)}: exit {proc.returncode}")
    return usage.ru_utime + usage.ru_stime


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("domain")
    ap.add_argument("problem")
    ap.add_argument("--tree", action="append", required=True, metavar="LABEL=SRC")
    ap.add_argument("--repeats", type=int, default=11)
    args = ap.parse_args(argv)
    trees = [t.split("=", 1) for t in args.tree]
    cmds = {
        "import": [sys.executable, "-c", "import nowplan.cli"],
        "plan": [sys.executable, "-c", CLI, "plan", args.domain, args.problem, "--json", "--improve", "0"],
        "run": [sys.executable, "-c", CLI, "run", args.domain, args.problem, "--criticality", "auto",
                "--strategy", "hpn", "--json"],
    }
    cpu: dict[tuple[str, str], list[float]] = {}
    load0 = os.getloadavg()[0]
    for _ in range(args.repeats):
        for label, src in trees:
            env = {**os.environ, "PYTHONPATH": os.path.abspath(src)}
            for name, cmd in cmds.items():
                cpu.setdefault((label, name), []).append(cpu_of(cmd, env))
    print(f"{args.domain} {args.problem}; {args.repeats} repeats, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, "
          f"load {load0:.1f} -> {os.getloadavg()[0]:.1f}; median process CPU s")
    print("| tree | " + " | ".join(cmds) + " | run - plan |")
    print("|---|" + "---|" * (len(cmds) + 1))
    for label, _ in trees:
        med = {n: statistics.median(cpu[(label, n)]) for n in cmds}
        print(f"| {label} | " + " | ".join(f"{med[n]:.3f}" for n in cmds) + f" | {med['run'] - med['plan']:.3f} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
