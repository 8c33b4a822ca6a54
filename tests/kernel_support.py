"""What the kernel-against-Python tests share: the bundled PDDL problems, the skip without a kernel, integer tasks.

The ``mode`` fixture (which code the next search uses) is in ``conftest.py``.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import cast

import pytest
from hypothesis import strategies as st

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


# costs of random actions: zero, fractions, huge and infinite ones
COSTS = st.sampled_from([0.0, 1.0, 1.0, 2.0, 3.0, 0.5, 0.1, 2.5, 3e6, math.inf])


@st.composite
def int_tasks(draw: st.DrawFn) -> Task:
    """Random small integer tasks (up to 9 facts, 14 actions)."""
    n = draw(st.integers(1, 9))
    fact = st.integers(0, n - 1)
    ids = st.lists(fact, max_size=3)
    actions = draw(st.lists(st.tuples(ids, st.lists(fact, min_size=1, max_size=3), ids, COSTS), max_size=14))
    return int_task(n, actions, draw(st.lists(fact, max_size=4)), draw(st.lists(fact, min_size=1, max_size=3)))
