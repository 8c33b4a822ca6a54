"""The ``nowplan`` CLI with one more domain, for tests/test_sweep_resume.py.

``logistics-gated`` has the logistics ``small`` scenario, except that a run of a seed at or
above ``$NOWPLAN_TEST_GATE_FROM`` waits while the file ``$NOWPLAN_TEST_GATE`` exists.  Every
run appends ``seed pid`` to ``$NOWPLAN_TEST_RUNLOG`` when it starts, so the test can count
how often each configuration was executed.  Workers are forked from this process, so they
see the registered domain.

Usage: ``python tests/gated_sweep.py sweep --domain logistics-gated ...``
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from nowplan.cli import main as cli_main
from nowplan.domains import registry
from nowplan.domains.registry import DomainSpec, Episode


def _gated(seed: int) -> Episode:
    gate = Path(os.environ["NOWPLAN_TEST_GATE"])
    with open(os.environ["NOWPLAN_TEST_RUNLOG"], "a", encoding="utf-8") as fh:  # one short append
        fh.write(f"{seed} {os.getpid()}\n")
    while seed >= int(os.environ["NOWPLAN_TEST_GATE_FROM"]) and gate.exists():
        time.sleep(0.02)
    return registry.get_domain("logistics").scenario("small")(seed)


def main(argv: list[str]) -> int:
    registry.register(DomainSpec("logistics-gated", "logistics small, held back by a gate file", {"small": _gated}))
    return cli_main(argv)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
