"""What the kernel-against-Python tests share: the bundled PDDL problems and the skip without a kernel.

The ``mode`` fixture (which code the next search uses) is in ``conftest.py``.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from nowplan.core.levels import flat_levels
from nowplan.io.pddl_read import load_pddl
from nowplan.planning import native
from nowplan.planning.task import Task, build_task

PDDL = Path(__file__).resolve().parents[1] / "src" / "nowplan" / "data" / "pddl"
PROBLEMS = sorted((d.name, p.name) for d in PDDL.iterdir() if d.is_dir() for p in d.glob("p*.pddl"))

_cls, _why = native._load()
needs_kernel = pytest.mark.skipif(_cls is None, reason=f"{_why}: only the Python code can be tested")


def pddl_task(domain: str, problem: str) -> Task:
    """The flat forward task of a bundled PDDL problem, with its own action costs."""
    p = load_pddl(str(PDDL / domain / "domain.pddl"), str(PDDL / domain / problem))
    return build_task(p.domain, p.objects, p.init, p.goal, flat_levels(), lambda a: a.cost(p.init))
