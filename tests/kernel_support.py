"""What the kernel-against-Python tests share: the bundled PDDL problems, the skip without a kernel, integer tasks.

The ``mode`` fixture (which code the next search uses) is in ``conftest.py``.
"""

from __future__ import annotations

from pathlib import Path
from typing import cast

import pytest

from nowplan.core.atoms import Atom
from nowplan.core.levels import flat_levels
from nowplan.core.operators import Action
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


def int_task(nfacts: int, actions: list[tuple[list[int], list[int], list[int], float]], init: list[int],
             goal: list[int]) -> Task:
    """A task in build_task's form (sorted ids, deletes not added) with stand-in atoms and actions."""
    pre = [tuple(sorted(set(p))) for p, _, _, _ in actions]
    add = [tuple(sorted(set(a))) for _, a, _, _ in actions]
    dele = [tuple(sorted(set(d) - set(a))) for (_, _, d, _), a in zip(actions, add, strict=True)]
    facts = [Atom(f"f{i}") for i in range(nfacts)]
    task = Task(facts, {a: i for i, a in enumerate(facts)}, cast(list[Action], list(range(len(actions)))),
                pre, add, dele, [c for _, _, _, c in actions], frozenset(init), tuple(sorted(set(goal))))
    task.index_preconditions()
    return task
