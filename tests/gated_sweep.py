"""The ``nowplan`` CLI with one more domain, for tests/test_sweep_resume.py.

``logistics-gated`` has the logistics ``small`` scenario, except that a run of a seed at or
above ``$NOWPLAN_TEST_GATE_FROM`` waits while the file ``$NOWPLAN_TEST_GATE`` exists.  Every
run appends ``seed pid run`` to ``$NOWPLAN_TEST_RUNLOG`` when it starts, so the test can count
how often each configuration was executed (the sweep's pre-check, which builds the scenario of the
first seed before any run, appends ``seed pid check`` and passes the gate).  Workers are forked from this process, so they
see the registered domain.

Usage: ``python tests/gated_sweep.py sweep --domain logistics-gated ...``
"""

from __future__ import annotations

import multiprocessing
import os
import sys
import time
from pathlib import Path

from nowplan.cli import main as cli_main
from nowplan.domains import registry
from nowplan.domains.registry import DomainSpec, Episode


def _gated(seed: int) -> Episode:
    gate = Path(os.environ["NOWPLAN_TEST_GATE"])
    # the sweep's pre-check (nowplan.experiments.precheck) builds a scenario in its own worker too
    kind = "check" if multiprocessing.current_process().name.startswith("nowplan-precheck") else "run"
    with open(os.environ["NOWPLAN_TEST_RUNLOG"], "a", encoding="utf-8") as fh:  # one short append
        fh.write(f"{seed} {os.getpid()} {kind}\n")
    if kind == "check":
        return registry.get_domain("logistics").scenario("small")(seed)
    while seed >= int(os.environ["NOWPLAN_TEST_GATE_FROM"]) and gate.exists():
        time.sleep(0.02)
    return registry.get_domain("logistics").scenario("small")(seed)


def main(argv: list[str]) -> int:
    registry.register(DomainSpec("logistics-gated", "logistics small, held back by a gate file", {"small": _gated}))
    return cli_main(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
